//! How deep a gel sinks under a normal force: each sensor's elastomer law.
//!
//! A gel is a thin layer of soft silicone bonded to a rigid window. Pressed lightly it follows a
//! thin-layer contact law, the indentation growing as a power of the force below Hertz's 2/3
//! (the layer stiffens as the contact widens past its thickness); pressed hard it bottoms out on
//! the window. [`Elastomer`] writes both as one smooth law:
//!
//! ```text
//! u(F) = c · F^p                      (thin-layer law, metres)
//! δ(F) = u / (1 + (u / δmax)^4)^(1/4)  (saturating at δmax, below the gel's thickness)
//! ```
//!
//! The parameters are fitted to the thin-layer (Shull) predictions over 5–20 N quoted in the
//! project's notes on tactile gels (Smooth-On Solaris or XP-565 silicone, Shore ≈ 10–15A, so
//! E ≈ 0.15–0.41 MPa by Gent's relation, ν ≈ 0.5):
//!
//! | sensor | E, layer, object radius | 5 N | 10 N | 20 N | p | δmax |
//! |---|---|---|---|---|---|---|
//! | DIGIT | 0.40 MPa, 3 mm, 20 mm | 0.39 | 0.51 | 0.66 mm | 0.38 | 1.5 mm (gel 2 mm) |
//! | GelSight 2014 | 0.15 MPa, 3 mm, 20 mm | 0.57 | 0.74 | 0.94 mm | 0.36 | 2.5 mm (gel 4 mm) |
//! | GelTip | 0.40 MPa, 3 mm, 10 mm | 0.60 | 0.79 | 1.03 mm | 0.39 | 2.0 mm (shell 2.5 mm) |
//!
//! For comparison, TACTO's DIGIT moves the object 0.05 mm/N up to 5 mm at 100 N, Taxim-robot's
//! tables give 0.58 mm at 6 N (GelSight) and 0.8–3 mm at 1–13 N (per object), and Isaac Lab's
//! TacSL notes that GelSight gels rarely sink more than 2.5 mm. A Robotiq 2F-85's 20–235 N
//! squeeze gives a DIGIT 0.65–1.33 mm: never the whole gel.
//!
//! The law is deterministic: the same force gives the same depth, byte for byte.

/// A gel's force → indentation law (see the [module docs](self)).
///
/// ```
/// use yarok_components::tactile::elastomer::Elastomer;
///
/// let digit = Elastomer::DIGIT;
/// assert_eq!(digit.indentation(0.0), 0.0);
/// let (light, firm) = (digit.indentation(5.0), digit.indentation(20.0));
/// assert!((light - 0.39e-3).abs() < 0.01e-3 && (firm - 0.65e-3).abs() < 0.02e-3);
/// assert!(digit.indentation(235.0) < digit.saturation && digit.saturation < 0.002);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastomer {
    /// `c`: the thin-layer law's indentation at 1 N (metres).
    pub compliance: f64,
    /// `p`: the thin-layer law's exponent of the force.
    pub exponent: f64,
    /// `δmax`: the depth the gel saturates at (metres), below its thickness.
    pub saturation: f64,
}

impl Elastomer {
    /// The DIGIT's gel (Smooth-On Solaris, E ≈ 0.40 MPa, 2 mm in the optical model).
    pub const DIGIT: Self = Self {
        compliance: 2.1157e-4,
        exponent: 0.38,
        saturation: 1.5e-3,
    };
    /// The GelSight 2014 fingertip's gel (XP-565, E ≈ 0.15 MPa, 4 mm in the optical model).
    pub const GELSIGHT2014: Self = Self {
        compliance: 3.1933e-4,
        exponent: 0.36,
        saturation: 2.5e-3,
    };
    /// The GelTip's elastomer shell (E ≈ 0.40 MPa, ≈ 2.5 mm over a curved tip).
    pub const GELTIP: Self = Self {
        compliance: 3.2030e-4,
        exponent: 0.39,
        saturation: 2.0e-3,
    };

    /// How deep (metres) the gel sinks under a normal `force` (newtons); 0 for no force or a
    /// pull, and never more than [`Elastomer::saturation`].
    pub fn indentation(&self, force: f64) -> f64 {
        if force.is_nan() || force <= 0.0 {
            return 0.0;
        }
        let thin_layer = self.compliance * force.powf(self.exponent);
        let ratio = (thin_layer / self.saturation).powi(4);
        if !ratio.is_finite() {
            return self.saturation;
        }
        thin_layer / (1.0 + ratio).sqrt().sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::Elastomer;

    #[test]
    fn the_thin_layer_points_are_met_and_the_law_saturates_below_the_gel() {
        for (law, points, thickness) in [
            (Elastomer::DIGIT, [0.39, 0.51, 0.66], 0.002),
            (Elastomer::GELSIGHT2014, [0.57, 0.74, 0.94], 0.004),
            (Elastomer::GELTIP, [0.60, 0.79, 1.03], 0.0025),
        ] {
            for (force, mm) in [5.0, 10.0, 20.0].into_iter().zip(points) {
                let thin_layer = law.compliance * f64::powf(force, law.exponent);
                assert!((thin_layer * 1e3 - mm).abs() < 0.02, "{law:?} at {force} N");
            }
            let mut last = 0.0;
            for force in [0.1, 1.0, 5.0, 20.0, 100.0, 235.0] {
                let depth = law.indentation(force);
                assert!(
                    depth > last && depth < law.saturation,
                    "{law:?} at {force} N"
                );
                last = depth;
            }
            for force in [1e300, f64::INFINITY] {
                assert!((law.indentation(force) - law.saturation).abs() < 1e-12);
            }
            assert!(law.saturation < thickness);
            assert_eq!(law.indentation(f64::NAN), 0.0);
            assert_eq!(law.indentation(-3.0), 0.0);
        }
    }
}
