//! Where on a sensor's image a press appears: the map from a press's described centre (where the
//! ball touched the gel, in the image's pixels at the nominal scale) to its imprint, fitted by the
//! calibration as the contact scale maps a press's described radius to its contact circle.

use super::surface::{HALF, on_half_line};

/// How far the imprints of the presses a calibration was fitted to lie from their described
/// centres: each by `shift` (columns, rows), and further from the image's middle by `stretch` of
/// their distance from it, per axis — the camera's offset and its lens's magnification over the
/// gel, or a bias of how the presses were described.
///
/// A press described at `(x, y)` of a `width × height` image appears at
/// `x + shift[0] + stretch[0] · (x − width / 2)`, and likewise for rows.
///
/// ```
/// use yarok_components::tactile::calibration::Placement;
///
/// let placement = Placement { shift: [0.0, -2.0], stretch: [0.05, 0.0] };
/// assert_eq!(placement.place([260.0, 100.0], 320, 240), [265.0, 98.0]);
/// assert_eq!(Placement::default().place([260.0, 100.0], 320, 240), [260.0, 100.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Placement {
    /// The imprints' offset, columns and rows (pixels).
    pub shift: [f64; 2],
    /// How much further from the image's middle the imprints lie, per axis, as a fraction of
    /// their described distance from it.
    pub stretch: [f64; 2],
}

/// The largest offset (pixels) and stretch (fraction) a placement may have: beyond, the
/// presses' described centres are not of these frames.
pub const PLACEMENT_LIMITS: [f64; 2] = [32.0, 0.25];

/// A placement beyond [`PLACEMENT_LIMITS`] ([`Placement::check`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("placement {name} {value}{unit} is beyond ±{most}{unit}")]
pub struct PlacementOutOfRange {
    /// `shift` or `stretch`.
    pub name: &'static str,
    /// The value beyond the limit.
    pub value: f64,
    /// The limit, either way.
    pub most: f64,
    /// The value's unit (` px` for a shift).
    pub unit: &'static str,
}

impl Placement {
    /// Where a press described at `centre` (column, row) of a `width × height` image appears.
    pub fn place(&self, centre: [f64; 2], width: usize, height: usize) -> [f64; 2] {
        let middle = [width as f64 / 2.0, height as f64 / 2.0];
        std::array::from_fn(|axis| {
            centre[axis] + self.shift[axis] + self.stretch[axis] * (centre[axis] - middle[axis])
        })
    }

    /// Whether every press appears where it is described.
    pub fn is_identity(&self) -> bool {
        *self == Self::default()
    }

    /// The placement that best explains (least squares, per axis) how far each press's imprint
    /// lies from its described centre: `moves` of (described centre, move to its imprint),
    /// pixels. An axis along which the presses' centres spread less than a tenth of the image
    /// (standard deviation) gets no stretch: their moves cannot tell it from noise.
    ///
    /// ```
    /// use yarok_components::tactile::calibration::Placement;
    ///
    /// // Presses across a 240 × 320 image, each imprint 1 px up and 5 % further out in columns.
    /// let moves: Vec<([f64; 2], [f64; 2])> = [[40.0, 60.0], [120.0, 160.0], [200.0, 260.0]]
    ///     .map(|c| (c, [0.05 * (c[0] - 120.0), -1.0]))
    ///     .to_vec();
    /// let placement = Placement::fit(&moves, 240, 320);
    /// assert!((placement.stretch[0] - 0.05).abs() < 1e-12 && (placement.shift[1] + 1.0).abs() < 1e-12);
    /// ```
    pub fn fit(moves: &[([f64; 2], [f64; 2])], width: usize, height: usize) -> Self {
        let middle = [width as f64 / 2.0, height as f64 / 2.0];
        let n = moves.len().max(1) as f64;
        let mut placement = Self::default();
        for axis in 0..2 {
            let from_middle = |centre: &[f64; 2]| centre[axis] - middle[axis];
            let mean_at = moves.iter().map(|(c, _)| from_middle(c)).sum::<f64>() / n;
            let mean_move = moves.iter().map(|(_, m)| m[axis]).sum::<f64>() / n;
            let spread: f64 = moves
                .iter()
                .map(|(c, _)| (from_middle(c) - mean_at).powi(2))
                .sum();
            let covariance: f64 = moves
                .iter()
                .map(|(c, m)| (from_middle(c) - mean_at) * (m[axis] - mean_move))
                .sum();
            let len = [width, height][axis] as f64;
            let stretch = if spread / n >= (len / 10.0).powi(2) {
                covariance / spread
            } else {
                0.0
            };
            placement.stretch[axis] = stretch;
            placement.shift[axis] = mean_move - stretch * mean_at;
        }
        placement
    }

    /// This placement of presses whose described centres are first moved as `moves` places
    /// them.
    pub(super) fn after_moves(&self, moves: &Placement) -> Self {
        Self {
            shift: std::array::from_fn(|a| {
                self.shift[a] + (1.0 + self.stretch[a]) * moves.shift[a]
            }),
            stretch: std::array::from_fn(|a| {
                (1.0 + self.stretch[a]) * (1.0 + moves.stretch[a]) - 1.0
            }),
        }
    }

    /// Checks the placement is within [`PLACEMENT_LIMITS`].
    ///
    /// # Errors
    ///
    /// [`PlacementOutOfRange`], naming the value out of range and the limit.
    pub fn check(&self) -> Result<(), PlacementOutOfRange> {
        let [most_shift, most_stretch] = PLACEMENT_LIMITS;
        for (name, values, most, unit) in [
            ("shift", self.shift, most_shift, " px"),
            ("stretch", self.stretch, most_stretch, ""),
        ] {
            if let Some(&value) = values.iter().find(|v| !(-most..=most).contains(*v)) {
                return Err(PlacementOutOfRange {
                    name,
                    value,
                    most,
                    unit,
                });
            }
        }
        Ok(())
    }

    /// Moves a half-resolution map (`half_width` points wide) of a `width × height` image's gel
    /// from where its presses are described to where they appear, into `placed`: each point takes
    /// the map's value (bilinear) where its position came from, the map's edge continuing
    /// beyond it.
    pub(super) fn place_half(
        &self,
        half: &[f64],
        half_width: usize,
        (width, height): (usize, usize),
        placed: &mut Vec<f64>,
    ) {
        let half_height = half.len() / half_width;
        let middle = [width as f64 / 2.0, height as f64 / 2.0];
        // A half point `h` is at image position `HALF·h + HALF/2`.
        let scale = HALF as f64;
        let source = |h: usize, axis: usize, len: usize| {
            let at = scale * h as f64 + scale / 2.0;
            let from =
                middle[axis] + (at - self.shift[axis] - middle[axis]) / (1.0 + self.stretch[axis]);
            on_half_line(from, len)
        };
        placed.clear();
        for hy in 0..half_height {
            let (y0, y1, fy) = source(hy, 1, half_height);
            for hx in 0..half_width {
                let (x0, x1, fx) = source(hx, 0, half_width);
                let value = (half[y0 * half_width + x0] * (1.0 - fx)
                    + half[y0 * half_width + x1] * fx)
                    * (1.0 - fy)
                    + (half[y1 * half_width + x0] * (1.0 - fx) + half[y1 * half_width + x1] * fx)
                        * fy;
                placed.push(value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: (usize, usize) = (240, 320);

    fn close(a: [f64; 2], b: [f64; 2], tolerance: f64) -> bool {
        a.iter().zip(b).all(|(a, b)| (a - b).abs() <= tolerance)
    }

    /// A smooth bump described at `centre`, on the half-resolution grid, is moved to where the
    /// placement puts the press: its centroid lands there.
    #[test]
    fn a_placed_map_shows_its_press_where_the_placement_puts_it() {
        let (width, height) = SIZE;
        let (half_width, half_height) = (width / HALF, height / HALF);
        let centre = [190.0, 70.0];
        let bump: Vec<f64> = (0..half_width * half_height)
            .map(|i| {
                let at = [(i % half_width) as f64, (i / half_width) as f64]
                    .map(|h| HALF as f64 * h + HALF as f64 / 2.0);
                let squared = (at[0] - centre[0]).powi(2) + (at[1] - centre[1]).powi(2);
                (-squared / (2.0 * 12.0_f64.powi(2))).exp()
            })
            .collect();
        let placement = Placement {
            shift: [1.5, -2.5],
            stretch: [0.05, -0.03],
        };
        let mut placed = Vec::new();
        placement.place_half(&bump, half_width, SIZE, &mut placed);
        let total: f64 = placed.iter().sum();
        let centroid = [0, 1].map(|axis| {
            placed
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let h = if axis == 0 {
                        i % half_width
                    } else {
                        i / half_width
                    };
                    v * (HALF as f64 * h as f64 + HALF as f64 / 2.0)
                })
                .sum::<f64>()
                / total
        });
        let expected = placement.place(centre, width, height);
        assert!(
            close(centroid, expected, 0.05),
            "{centroid:?}, expected {expected:?}"
        );
        assert!(!close(centroid, centre, 2.0));
    }

    /// Moves made by a placement are explained by that placement.
    #[test]
    fn the_fit_recovers_the_placement_that_made_the_moves() {
        let made = Placement {
            shift: [0.8, -2.0],
            stretch: [0.045, 0.01],
        };
        let moves: Vec<([f64; 2], [f64; 2])> = [[30.0, 40.0], [200.0, 90.0], [120.0, 300.0]]
            .into_iter()
            .map(|c| {
                let placed = made.place(c, SIZE.0, SIZE.1);
                (c, [placed[0] - c[0], placed[1] - c[1]])
            })
            .collect();
        let found = Placement::fit(&moves, SIZE.0, SIZE.1);
        assert!(close(found.shift, made.shift, 1e-9) && close(found.stretch, made.stretch, 1e-9));
    }

    /// A placement after moves places each press where it would place the moved press.
    #[test]
    fn a_placement_after_moves_places_the_moved_press() {
        let first = Placement {
            shift: [1.0, -2.0],
            stretch: [0.04, 0.0],
        };
        let moves = Placement {
            shift: [-0.5, 0.25],
            stretch: [0.01, 0.02],
        };
        let composed = first.after_moves(&moves);
        for centre in [[10.0, 20.0], [230.0, 310.0], [120.0, 160.0]] {
            let (width, height) = SIZE;
            let expected = first.place(moves.place(centre, width, height), width, height);
            assert!(close(composed.place(centre, width, height), expected, 1e-9));
        }
    }

    #[test]
    fn a_placement_beyond_its_limits_is_refused_by_name() {
        let far = Placement {
            shift: [40.0, 0.0],
            stretch: [0.0; 2],
        };
        assert!(far.check().unwrap_err().to_string().contains("shift 40 px"));
        assert!(Placement::default().check().is_ok());
    }
}
