//! The `joints_csv` recorder's file, which recordings read back by others' tools are checked
//! against.

/// A `joints_csv` file: its header and its rows of numbers (`time` first).
pub(crate) struct JointsCsv {
    header: Vec<String>,
    pub(crate) rows: Vec<Vec<f64>>,
}

impl JointsCsv {
    pub(crate) fn read(path: &std::path::Path) -> Self {
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        Self { header, rows }
    }

    /// Asserts that `states` — each `TIME POSITION...` as `reader` printed a joint state, the
    /// positions those of the coordinates `names` — are the rows, one for one: the times within
    /// a nanosecond, the positions equal and bit for bit.
    pub(crate) fn assert_positions(&self, names: &[&str], states: &[&str], reader: &str) {
        let columns: Vec<usize> = names
            .iter()
            .map(|name| {
                // `joint` is `joint.pos`; coordinate `joint[k]` of a free joint, `joint.pos[k]`.
                let column = match name.split_once('[') {
                    Some((joint, index)) => format!("{joint}.pos[{index}"),
                    None => format!("{name}.pos"),
                };
                self.header
                    .iter()
                    .position(|h| *h == column)
                    .unwrap_or_else(|| panic!("no column {column} in {:?}", self.header))
            })
            .collect();
        assert_eq!(states.len(), self.rows.len(), "{reader}");
        for (state, row) in states.iter().zip(&self.rows) {
            let state: Vec<f64> = state.split(' ').map(|v| v.parse().unwrap()).collect();
            assert!(
                (state[0] - row[0]).abs() < 1e-9,
                "{reader}: times {} {}",
                state[0],
                row[0]
            );
            let positions: Vec<f64> = columns.iter().map(|c| row[*c]).collect();
            let same = state[1..].len() == positions.len()
                && state[1..]
                    .iter()
                    .zip(&positions)
                    .all(|(a, b)| a == b && a.to_bits() == b.to_bits());
            assert!(
                same,
                "{reader} at {} s: {:?} against {positions:?}",
                row[0],
                &state[1..]
            );
        }
    }
}
