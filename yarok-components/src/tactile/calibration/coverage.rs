//! [`Coverage`]: where on the gel a set of calibration presses reached, and where the model
//! holds the nearest covered weights instead of extrapolating.

use image::RgbImage;

use super::press::Press;
use super::surface::{Area, position};

/// Where a set of calibration presses reached on a `width × height` gel: the pixels within a
/// press's imprint (its radius of its centre), and the smallest rectangle holding them all,
/// beyond which a calibration holds the colour weights of the rectangle's nearest point.
///
/// ```
/// use image::RgbImage;
/// use yarok_components::tactile::calibration::{Coverage, Press};
///
/// let press = Press { frame: RgbImage::new(40, 20), centre: [10.0, 10.0], radius: 5.0 };
/// let coverage = Coverage::of(&[press], 40, 20);
/// assert_eq!(coverage.rectangle(), [5, 5, 15, 15]);
/// assert!((coverage.outside_share() - 0.875).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Coverage {
    width: u32,
    height: u32,
    reached: Vec<bool>,
    /// Columns and rows, `[x_min, y_min, x_max, y_max]`, the end ones excluded.
    rectangle: [u32; 4],
}

impl Coverage {
    /// Where `presses` reached on a `width × height` gel.
    pub fn of(presses: &[Press], width: u32, height: u32) -> Self {
        let mut reached = vec![false; width as usize * height as usize];
        let mut rectangle = [width, height, 0, 0];
        for press in presses {
            let [cx, cy] = press.centre;
            let r = press.radius;
            let span = |centre: f64, limit: u32| {
                let low = (centre - r).floor().clamp(0.0, f64::from(limit)) as u32;
                let high = (centre + r).ceil().clamp(0.0, f64::from(limit)) as u32;
                (low, high)
            };
            let ((x0, x1), (y0, y1)) = (span(cx, width), span(cy, height));
            rectangle = [
                rectangle[0].min(x0),
                rectangle[1].min(y0),
                rectangle[2].max(x1),
                rectangle[3].max(y1),
            ];
            for y in y0..y1 {
                for x in x0..x1 {
                    let (dx, dy) = (f64::from(x) + 0.5 - cx, f64::from(y) + 0.5 - cy);
                    if dx * dx + dy * dy < r * r {
                        reached[(y * width + x) as usize] = true;
                    }
                }
            }
        }
        if rectangle[0] >= rectangle[2] || rectangle[1] >= rectangle[3] {
            rectangle = [0, 0, width, height];
        }
        Self {
            width,
            height,
            reached,
            rectangle,
        }
    }

    /// The share of the gel within some press's imprint.
    pub fn reached_share(&self) -> f64 {
        let reached = self.reached.iter().filter(|r| **r).count();
        reached as f64 / self.reached.len().max(1) as f64
    }

    /// The smallest rectangle holding every imprint: `[x_min, y_min, x_max, y_max]`, pixels,
    /// the maxima excluded.
    pub fn rectangle(&self) -> [u32; 4] {
        self.rectangle
    }

    /// The share of the gel outside [`Coverage::rectangle`], where no press reached and the
    /// model holds the nearest covered weights.
    pub fn outside_share(&self) -> f64 {
        let [x0, y0, x1, y1] = self.rectangle.map(f64::from);
        1.0 - (x1 - x0) * (y1 - y0) / (f64::from(self.width) * f64::from(self.height))
    }

    /// The coverage as an image of the gel: white where a press reached, grey elsewhere in the
    /// rectangle, black outside it.
    pub fn map(&self) -> RgbImage {
        let [x0, y0, x1, y1] = self.rectangle;
        RgbImage::from_fn(self.width, self.height, |x, y| {
            let level = if self.reached[(y * self.width + x) as usize] {
                255
            } else if (x0..x1).contains(&x) && (y0..y1).contains(&y) {
                128
            } else {
                0
            };
            image::Rgb([level; 3])
        })
    }

    /// The rectangle in the position terms' coordinates.
    pub(super) fn area(&self) -> Area {
        let (width, height) = (self.width as usize, self.height as usize);
        let [x0, y0, x1, y1] = self.rectangle.map(f64::from);
        let low = position(x0, y0, width, height);
        let high = position(x1, y1, width, height);
        [low[0], low[1], high[0], high[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::super::Calibration;

    /// A flat press (the whole gel sunk 0.856 mm, as a grasped block's face sinks the DIGIT's):
    /// outside the rectangle the bundled calibration's presses reached, each pixel changes as
    /// the rectangle's nearest point does — the colour polynomial is not run beyond the data.
    #[test]
    fn beyond_the_presses_a_flat_press_changes_as_the_nearest_covered_point() {
        let digit = Calibration::digit();
        let (width, height) = digit.size();
        let metres_per_pixel = 1e-3 / digit.geometry().pixels_per_mm;
        let flat = vec![0.856e-3_f32; width * height];
        let image = digit.render_indentation(&flat, metres_per_pixel).unwrap();
        let change = |x: u32, y: u32| {
            let (seen, untouched) = (
                image.get_pixel(x, y).0,
                digit.background().get_pixel(x, y).0,
            );
            std::array::from_fn::<i32, 3, _>(|c| i32::from(seen[c]) - i32::from(untouched[c]))
        };
        // The bundled presses' rectangle: columns 19-233, rows 39-266 of 240 × 320.
        let [x0, y0, x1, y1] = [19, 39, 233, 266];
        for (corner, nearest) in [
            ((0, 0), (x0 + 1, y0 + 1)),
            ((239, 0), (x1 - 2, y0 + 1)),
            ((0, 319), (x0 + 1, y1 - 2)),
            ((239, 319), (x1 - 2, y1 - 2)),
        ] {
            let (outside, inside) = (change(corner.0, corner.1), change(nearest.0, nearest.1));
            for c in 0..3 {
                assert!(
                    (outside[c] - inside[c]).abs() <= 2,
                    "{corner:?} changes by {outside:?}, its nearest covered point {nearest:?} by \
                     {inside:?}"
                );
            }
        }
    }
}
