//! Reading a user's text file within a stated size, so that a path to a device that never
//! ends (`/dev/zero`) or a runaway file is refused naming the limit instead of filling memory.

use std::io::Read;
use std::path::Path;

/// The most a run configuration (`--config`) may hold: hand-written settings are kilobytes.
pub const CONFIG_LIMIT: u64 = 1 << 20;

/// The most a template, an included model file or a data file (a press list, a calibration)
/// may hold: the largest published MJCF files are a few megabytes.
pub const TEMPLATE_LIMIT: u64 = 64 << 20;

/// The text of the file at `path`, read no further than `limit` bytes.
///
/// # Errors
///
/// When it cannot be opened or read; when it holds more than `limit` bytes
/// ([`std::io::ErrorKind::FileTooLarge`], said with the limit), or is not UTF-8
/// ([`std::io::ErrorKind::InvalidData`]).
///
/// # Examples
///
/// ```
/// let error = yarok_core::bounded::read_text("/dev/zero".as_ref(), 1024).unwrap_err();
/// assert_eq!(error.to_string(), "it holds more than 1 KiB, the most read from such a file");
/// ```
pub fn read_text(path: &Path, limit: u64) -> std::io::Result<String> {
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!(
                "it holds more than {}, the most read from such a file",
                in_binary_units(limit)
            ),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "it is not UTF-8 text (byte {} is not)",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// `bytes` in KiB, MiB or GiB when whole, else in bytes.
fn in_binary_units(bytes: u64) -> String {
    for (unit, size) in [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)] {
        if bytes >= size && bytes.is_multiple_of(size) {
            return format!("{} {unit}", bytes / size);
        }
    }
    format!("{bytes} bytes")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_within_its_limit_is_read_whole_and_one_byte_over_is_refused() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("settings.toml");
        std::fs::write(&path, "a = 1\n").unwrap();
        assert_eq!(read_text(&path, 6).unwrap(), "a = 1\n");
        assert_eq!(
            read_text(&path, 5).unwrap_err().to_string(),
            "it holds more than 5 bytes, the most read from such a file"
        );
        std::fs::write(&path, b"a = \xff\n").unwrap();
        assert_eq!(
            read_text(&path, 100).unwrap_err().to_string(),
            "it is not UTF-8 text (byte 4 is not)"
        );
        assert_eq!(in_binary_units(CONFIG_LIMIT), "1 MiB");
        assert_eq!(in_binary_units(TEMPLATE_LIMIT), "64 MiB");
    }
}
