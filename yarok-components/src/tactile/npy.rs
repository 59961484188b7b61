//! Float arrays in NumPy `.npy` files: read plain or gzip-compressed (`.npy.gz`), written plain.

use std::io::Read;
use std::path::Path;

/// A float32 array read from a `.npy` file.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// Dimensions, outermost first.
    pub shape: Vec<usize>,
    /// Elements in C order.
    pub data: Vec<f32>,
}

yarok_core::debug_as_report!(NpyError);

/// The mark in the header of the `.npy` files yarok writes, after the header's dictionary: a
/// Python comment, which NumPy's reader skips.
const WRITTEN_BY_YAROK: &str = "# written by yarok";

/// Whether the file at `path` is a `.npy` file yarok wrote: its header holds yarok's mark.
///
/// # Errors
///
/// When the file cannot be read.
pub fn written_by_yarok(path: &Path) -> std::io::Result<bool> {
    let head = yarok_core::output::head(path, 4096)?;
    let Some(header) = head.get(10..) else {
        return Ok(false);
    };
    let header = String::from_utf8_lossy(header);
    Ok(head.starts_with(b"\x93NUMPY")
        && header
            .split('\n')
            .next()
            .is_some_and(|line| line.trim_end().ends_with(WRITTEN_BY_YAROK)))
}

/// Why a `.npy` file could not be read or written.
#[derive(thiserror::Error)]
#[non_exhaustive]
pub enum NpyError {
    /// The file could not be read or decompressed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not written where it was asked to be.
    #[error(transparent)]
    Refused(#[from] yarok_core::OutputError),
    /// The content is not a little-endian float32 or float64 `.npy` array in C order.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

/// Reads a `.npy` or `.npy.gz` file of `<f4` or `<f8` values (float64 is narrowed to float32).
///
/// # Errors
///
/// [`NpyError`] naming the file.
pub fn read(path: impl AsRef<Path>) -> Result<NpyArray, NpyError> {
    let path = path.as_ref();
    let name = path.display().to_string();
    let io = |source| NpyError::Io {
        path: name.clone(),
        source,
    };
    let raw = std::fs::read(path).map_err(io)?;
    let bytes = if path.extension().is_some_and(|e| e == "gz") {
        let mut decompressed = Vec::new();
        flate2::read::GzDecoder::new(raw.as_slice())
            .take(MAX_DECOMPRESSED + 1)
            .read_to_end(&mut decompressed)
            .map_err(io)?;
        if decompressed.len() as u64 > MAX_DECOMPRESSED {
            return Err(NpyError::Format {
                path: name,
                message: format!(
                    "decompresses to more than {} MiB, more than any depth map",
                    MAX_DECOMPRESSED >> 20
                ),
            });
        }
        decompressed
    } else {
        raw
    };
    parse(&bytes).map_err(|message| NpyError::Format {
        path: name,
        message,
    })
}

/// The most a `.npy.gz` may decompress to: 1 GiB (a 16384 × 16384 float64 map is 2 GiB less
/// than twice that; depth maps are far smaller).
const MAX_DECOMPRESSED: u64 = 1 << 30;

/// Parses the bytes of a `.npy` file.
///
/// # Errors
///
/// A message saying what is wrong.
pub fn parse(bytes: &[u8]) -> Result<NpyArray, String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a .npy file".into());
    }
    let (header_len, header_start) = match bytes[6] {
        1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        version => return Err(format!("unsupported .npy version {version}")),
    };
    let header = bytes
        .get(header_start..header_start + header_len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or("truncated header")?;
    if header.contains("'fortran_order': True") {
        return Err("Fortran-ordered arrays are not supported".into());
    }
    let width = if header.contains("'descr': '<f4'") {
        4
    } else if header.contains("'descr': '<f8'") {
        8
    } else {
        return Err(format!(
            "only little-endian float32/float64 arrays are supported: {header}"
        ));
    };
    let shape_text = header
        .split("'shape': (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .ok_or("no shape in the header")?;
    let shape: Vec<usize> = shape_text
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| format!("bad shape ({shape_text})")))
        .collect::<Result<_, _>>()?;
    let expected = shape
        .iter()
        .try_fold(width, |n: usize, d| n.checked_mul(*d))
        .ok_or_else(|| format!("shape {shape:?} is too large"))?;
    let body = &bytes[header_start + header_len..];
    if body.len() != expected {
        return Err(format!(
            "{} data bytes for shape {shape:?}, expected {expected}",
            body.len(),
        ));
    }
    let data = if width == 4 {
        body.chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    } else {
        body.chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().unwrap_or([0; 8])) as f32)
            .collect()
    };
    Ok(NpyArray { shape, data })
}

impl NpyArray {
    /// The bytes of a `.npy` file (version 1.0, little-endian float32, C order) holding this
    /// array: what `numpy.load` reads.
    ///
    /// ```
    /// use yarok_components::tactile::npy::{NpyArray, parse};
    ///
    /// let array = NpyArray { shape: vec![2, 3], data: vec![0.5; 6] };
    /// assert_eq!(parse(&array.to_bytes())?, array);
    /// # Ok::<(), String>(())
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let dimensions: String = self.shape.iter().map(|d| format!("{d}, ")).collect();
        let shape = match self.shape.len() {
            1 => dimensions.trim_end_matches(' ').to_owned(),
            _ => dimensions.trim_end_matches(", ").to_owned(),
        };
        let mut header = format!(
            "{{'descr': '<f4', 'fortran_order': False, 'shape': ({shape}), }} {WRITTEN_BY_YAROK}"
        );
        // The magic, version and length take 10 bytes; the header ends in a newline and pads
        // the data to a multiple of 64 bytes.
        let padded = (10 + header.len() + 1).div_ceil(64) * 64 - 10;
        header.extend(std::iter::repeat_n(' ', padded - header.len() - 1));
        header.push('\n');
        let mut bytes = Vec::with_capacity(10 + header.len() + 4 * self.data.len());
        bytes.extend_from_slice(b"\x93NUMPY\x01\x00");
        bytes.extend_from_slice(
            &u16::try_from(header.len())
                .unwrap_or(u16::MAX)
                .to_le_bytes(),
        );
        bytes.extend_from_slice(header.as_bytes());
        for value in &self.data {
            bytes.extend_from_slice(&value.to_le_bytes());
        }
        bytes
    }

    /// Writes this array to a `.npy` file (see [`NpyArray::to_bytes`]), replacing only a
    /// `.npy` file yarok wrote ([`written_by_yarok`]).
    ///
    /// # Errors
    ///
    /// [`NpyError::Refused`] when a file yarok did not write is at `path` (it is left as it
    /// is) or it cannot be written, naming the file.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<(), NpyError> {
        let path = path.as_ref();
        yarok_core::output_file::write_output(
            path,
            "depth map",
            written_by_yarok,
            &self.to_bytes(),
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn parses_a_small_array_and_refuses_garbage() {
        let header = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 1), }";
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
        bytes.extend_from_slice(header.as_bytes());
        bytes.extend_from_slice(&1.5f32.to_le_bytes());
        bytes.extend_from_slice(&(-2.0f32).to_le_bytes());
        let array = super::parse(&bytes).unwrap();
        assert_eq!((array.shape, array.data), (vec![2, 1], vec![1.5, -2.0]));
        assert!(
            super::parse(&bytes[..bytes.len() - 1])
                .unwrap_err()
                .contains("data bytes")
        );
        assert!(super::parse(b"hello").is_err());
    }

    /// A 128-byte file may declare any shape: one whose size overflows, or is far larger than
    /// the file, is refused before anything is allocated for it.
    #[test]
    fn huge_or_overflowing_shapes_are_refused_without_allocating() {
        for shape in [
            "(9223372036854775807,)",
            "(4294967296, 4294967296)",
            "(2305843009213693952,)",
        ] {
            let header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
            let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
            bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
            bytes.extend_from_slice(header.as_bytes());
            bytes.resize(128, 0);
            let error = super::parse(&bytes).unwrap_err();
            assert!(
                error.contains("too large") || error.contains("data bytes"),
                "{shape}: {error}"
            );
        }
    }

    /// A small `.npy.gz` that inflates to gigabytes (a zip bomb) is refused once past 1 GiB.
    #[test]
    fn a_gzip_that_inflates_beyond_any_depth_map_is_refused() {
        use std::io::Write;
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("bomb.npy.gz");
        let mut encoder = flate2::write::GzEncoder::new(
            std::fs::File::create(&path).unwrap(),
            flate2::Compression::fast(),
        );
        let zeros = vec![0u8; 1 << 20];
        for _ in 0..1100 {
            encoder.write_all(&zeros).unwrap();
        }
        encoder.finish().unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() < 8 << 20);
        let error = super::read(&path).unwrap_err().to_string();
        assert!(
            error.contains("more than 1024 MiB") && error.contains("bomb.npy.gz"),
            "{error}"
        );
    }

    #[test]
    fn written_arrays_read_back_with_an_aligned_header() {
        for shape in [vec![3], vec![2, 1], vec![4, 3, 2]] {
            let count = shape.iter().product();
            let array = super::NpyArray {
                shape: shape.clone(),
                data: (0..count).map(|i| i as f32 / 3.0).collect(),
            };
            let bytes = array.to_bytes();
            assert_eq!((bytes.len() - 4 * count) % 64, 0, "{shape:?}");
            assert_eq!(super::parse(&bytes).unwrap(), array);
        }
        let header = String::from_utf8_lossy(
            &super::NpyArray {
                shape: vec![3],
                data: vec![0.0; 3],
            }
            .to_bytes()[10..],
        )
        .into_owned();
        assert!(
            header.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }"),
            "{header}"
        );
    }
}
