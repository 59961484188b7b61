//! Command-line arguments as the OS gives them: paths and values are taken as UTF-8, and one
//! that is not is refused naming its position and what it looks like, never a panic.

use std::ffi::OsString;

/// `arg`, the `position`-th argument (from 1, after the program's name), as UTF-8.
///
/// # Errors
///
/// When it is not UTF-8: a message naming its position and showing it with the bytes that are
/// not replaced by `\u{FFFD}`.
///
/// # Examples
///
/// ```
/// use std::ffi::OsString;
/// use std::os::unix::ffi::OsStringExt;
///
/// assert_eq!(yarok_core::args::utf8(1, OsString::from("run")), Ok("run".to_owned()));
/// let error = yarok_core::args::utf8(3, OsString::from_vec(b"out/caf\xe9.mcap".to_vec()));
/// assert_eq!(
///     error.unwrap_err(),
///     "argument 3 (\"out/caf\u{FFFD}.mcap\") is not UTF-8: give paths and values in UTF-8 \
///      (rename the file, or pass another path to it)"
/// );
/// ```
pub fn utf8(position: usize, arg: OsString) -> Result<String, String> {
    arg.into_string().map_err(|arg| {
        format!(
            "argument {position} ({:?}) is not UTF-8: give paths and values in UTF-8 (rename \
             the file, or pass another path to it)",
            arg.to_string_lossy()
        )
    })
}

/// The process's arguments after its name, each as UTF-8.
///
/// # Errors
///
/// As [`utf8`], for the first that is not.
pub fn from_process() -> Result<Vec<String>, String> {
    std::env::args_os()
        .skip(1)
        .enumerate()
        .map(|(index, arg)| utf8(index + 1, arg))
        .collect()
}
