//! Errors printed for people.
//!
//! `fn main() -> Result<(), E>` prints a returned error with `{:?}`, so yarok's error types
//! format their `Debug` as their message followed by the causes it does not already include,
//! instead of a dump of their fields.

use std::error::Error;
use std::fmt;

/// Writes `error`'s message, then, under "Caused by:", each cause whose text the lines before
/// do not already contain.
///
/// # Examples
///
/// ```
/// use std::fmt;
///
/// #[derive(thiserror::Error)]
/// #[error("cannot load the world")]
/// struct LoadError(#[source] std::io::Error);
///
/// impl fmt::Debug for LoadError {
///     fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
///         yarok_core::report::write_report(self, f)
///     }
/// }
///
/// let error = LoadError(std::io::Error::other("disk on fire"));
/// assert_eq!(format!("{error:?}"), "cannot load the world\n\nCaused by:\n    disk on fire");
/// ```
pub fn write_report(error: &dyn Error, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    let mut shown = error.to_string();
    f.write_str(&shown)?;
    let mut heading = true;
    let mut source = error.source();
    while let Some(cause) = source {
        let text = cause.to_string();
        if !shown.contains(&text) {
            if heading {
                f.write_str("\n\nCaused by:")?;
                heading = false;
            }
            write!(f, "\n    {text}")?;
            shown.push_str(&text);
        }
        source = cause.source();
    }
    Ok(())
}

/// `error`'s message followed by each cause it does not already include, on one line,
/// separated by `: ` (for an error a larger message quotes).
///
/// # Examples
///
/// ```
/// let error = std::io::Error::other("no space left on device");
/// let wrapped = std::io::Error::new(std::io::ErrorKind::Other, error);
/// assert_eq!(yarok_core::report::one_line(&wrapped), "no space left on device");
/// ```
pub fn one_line(error: &dyn Error) -> String {
    let mut shown = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        let text = cause.to_string();
        if !shown.contains(&text) {
            shown.push_str(": ");
            shown.push_str(&text);
        }
        source = cause.source();
    }
    shown
}

/// Implements `Debug` for error types as [`write_report`].
#[macro_export]
macro_rules! debug_as_report {
    ($($error:ty),+ $(,)?) => {
        $(
            impl ::std::fmt::Debug for $error {
                fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                    $crate::report::write_report(self, f)
                }
            }
        )+
    };
}
