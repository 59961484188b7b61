//! [`Cdr`]: messages in the Common Data Representation as ROS 2 serialises them (plain CDR,
//! little-endian, after its 4-byte encapsulation header), the bytes `ros2 bag` records.

/// A message being serialised: each value aligned to its own size, counted from the end of the
/// encapsulation header.
#[derive(Debug)]
pub(crate) struct Cdr {
    bytes: Vec<u8>,
}

/// The encapsulation header of plain little-endian CDR (`CDR_LE`), options zero.
const CDR_LE: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

impl Cdr {
    pub(crate) fn new() -> Self {
        Self {
            bytes: CDR_LE.to_vec(),
        }
    }

    /// Pads with zeros until the next value, of `size` bytes, is aligned.
    fn align(&mut self, size: usize) {
        let offset = self.bytes.len() - CDR_LE.len();
        let padding = (size - offset % size) % size;
        self.bytes.resize(self.bytes.len() + padding, 0);
    }

    pub(crate) fn u8(&mut self, value: u8) -> &mut Self {
        self.bytes.push(value);
        self
    }

    pub(crate) fn u32(&mut self, value: u32) -> &mut Self {
        self.align(4);
        self.bytes.extend_from_slice(&value.to_le_bytes());
        self
    }

    pub(crate) fn i32(&mut self, value: i32) -> &mut Self {
        self.align(4);
        self.bytes.extend_from_slice(&value.to_le_bytes());
        self
    }

    pub(crate) fn f64(&mut self, value: f64) -> &mut Self {
        self.align(8);
        self.bytes.extend_from_slice(&value.to_le_bytes());
        self
    }

    /// A sequence's or string's length. Longer than `u32::MAX` cannot be said in CDR: the
    /// messages yarok records are far smaller.
    fn length(&mut self, length: usize) -> &mut Self {
        self.u32(u32::try_from(length).expect("a CDR sequence holds at most u32::MAX values"))
    }

    /// A string: its length counting the terminating NUL, its bytes, the NUL.
    pub(crate) fn string(&mut self, value: &str) -> &mut Self {
        self.length(value.len() + 1);
        self.bytes.extend_from_slice(value.as_bytes());
        self.bytes.push(0);
        self
    }

    /// A `uint8[]`.
    pub(crate) fn bytes(&mut self, values: &[u8]) -> &mut Self {
        self.length(values.len());
        self.bytes.extend_from_slice(values);
        self
    }

    /// A `float64[]`.
    pub(crate) fn f64s(&mut self, values: &[f64]) -> &mut Self {
        self.length(values.len());
        for value in values {
            self.f64(*value);
        }
        self
    }

    /// A `string[]`.
    pub(crate) fn strings<'a>(
        &mut self,
        values: impl ExactSizeIterator<Item = &'a str>,
    ) -> &mut Self {
        self.length(values.len());
        for value in values {
            self.string(value);
        }
        self
    }

    /// A sequence of `values`, each written by `each`.
    pub(crate) fn sequence<T>(
        &mut self,
        values: impl ExactSizeIterator<Item = T>,
        mut each: impl FnMut(&mut Self, T),
    ) -> &mut Self {
        self.length(values.len());
        for value in values {
            each(self, value);
        }
        self
    }

    /// A `builtin_interfaces/Time` of `nanoseconds` since the epoch (of the platform's clock).
    pub(crate) fn time(&mut self, nanoseconds: u64) -> &mut Self {
        let seconds = i32::try_from(nanoseconds / 1_000_000_000).unwrap_or(i32::MAX);
        self.i32(seconds).u32((nanoseconds % 1_000_000_000) as u32)
    }

    pub(crate) fn finish(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_aligned_to_their_size_after_the_header() {
        let bytes = Cdr::new().u8(7).f64(1.5).string("ab").u32(3).finish();
        let mut expected = vec![0, 1, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0];
        expected.extend_from_slice(&1.5f64.to_le_bytes());
        expected.extend_from_slice(&[3, 0, 0, 0, b'a', b'b', 0, 0, 3, 0, 0, 0]);
        assert_eq!(bytes, expected);
    }

    #[test]
    fn sequences_and_times() {
        let bytes = Cdr::new()
            .time(3_000_000_005)
            .f64s(&[2.0])
            .bytes(&[9, 8])
            .finish();
        // The float64 after the sequence's length waits for the next multiple of 8.
        let mut expected = vec![0, 1, 0, 0, 3, 0, 0, 0, 5, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0];
        expected.extend_from_slice(&2.0f64.to_le_bytes());
        expected.extend_from_slice(&[2, 0, 0, 0, 9, 8]);
        assert_eq!(bytes, expected);
    }
}
