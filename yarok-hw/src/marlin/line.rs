//! Numbered, checksummed command lines: `N<n> <command>*<checksum>`, the checksum the XOR of
//! every byte before the `*`.

use super::MarlinError;

/// The bytes of `command` sent as line `number`, with its checksum and a newline.
///
/// # Errors
///
/// [`MarlinError::InvalidCommand`] for an empty command or one holding a character the line
/// format reserves (`*`, `;`, a line break) or a non-ASCII one.
///
/// ```
/// assert_eq!(yarok_hw::marlin::numbered_line(1, "G28")?, b"N1 G28*18\n");
/// # Ok::<(), yarok_hw::marlin::MarlinError>(())
/// ```
pub fn numbered_line(number: u64, command: &str) -> Result<Vec<u8>, MarlinError> {
    let reserved = |c: char| !c.is_ascii() || c.is_ascii_control() || c == '*' || c == ';';
    if command.trim().is_empty() || command.contains(reserved) {
        return Err(MarlinError::InvalidCommand {
            command: command.to_owned(),
        });
    }
    let body = format!("N{number} {}", command.trim());
    let checksum = body.bytes().fold(0u8, |sum, byte| sum ^ byte);
    Ok(format!("{body}*{checksum}\n").into_bytes())
}
