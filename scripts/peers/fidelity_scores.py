"""Scores a simulated tactile image against a real one as the field measures them, with
scikit-image and NumPy (an independent reader of yarok's own measures).

usage: fidelity_scores.py REAL.png REAL_UNTOUCHED.png SIM.png SIM_UNTOUCHED.png CX CY RADIUS

Prints `name value` lines: whole_ssim (skimage's default structural_similarity), contact_ssim
(the mean over the disc of the channel-averaged SSIM map), whole_mae, contact_mae, whole_psnr,
contact_psnr, and change_correlation_{r,g,b} (Pearson over the disc of frame − untouched against
sim − sim untouched).
"""

import sys

import numpy as np
from PIL import Image
from skimage.metrics import structural_similarity


def rgb(path):
    return np.asarray(Image.open(path).convert("RGB")).astype(np.float64)


def main():
    real, real_untouched, sim, sim_untouched = (rgb(p) for p in sys.argv[1:5])
    cx, cy, radius = (float(v) for v in sys.argv[5:8])
    height, width, _ = real.shape
    y, x = np.mgrid[0:height, 0:width]
    disc = (x + 0.5 - cx) ** 2 + (y + 0.5 - cy) ** 2 < radius**2
    whole, ssim_map = structural_similarity(
        real.astype(np.uint8), sim.astype(np.uint8), channel_axis=2, data_range=255, full=True
    )
    error = real - sim
    print("whole_ssim", repr(float(whole)))
    print("contact_ssim", repr(float(ssim_map.mean(axis=2)[disc].mean())))
    print("whole_mae", repr(float(np.abs(error).mean())))
    print("contact_mae", repr(float(np.abs(error)[disc].mean())))
    print("whole_psnr", repr(float(10 * np.log10(255**2 / (error**2).mean()))))
    print("contact_psnr", repr(float(10 * np.log10(255**2 / (error[disc] ** 2).mean()))))
    real_change = (real - real_untouched)[disc]
    sim_change = (sim - sim_untouched)[disc]
    for channel, name in enumerate("rgb"):
        correlation = np.corrcoef(real_change[:, channel], sim_change[:, channel])[0, 1]
        print(f"change_correlation_{name}", repr(float(correlation)))


if __name__ == "__main__":
    main()
