//! [`Reply`]: what a line from a Marlin printer means, for stock Marlin 1.1/2.x and OctoPrint's
//! VirtualPrinter alike. Parsing is total: any bytes give a reply, never a panic.

/// A position the printer reported (`M114`), in millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position {
    /// X.
    pub x: f64,
    /// Y.
    pub y: f64,
    /// Z.
    pub z: f64,
}

/// What a line from the printer means to the driver.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Reply {
    /// `ok`: the command was accepted (queued, for moves). The VirtualPrinter puts `M114`'s
    /// position on this line.
    Ok {
        /// A position on the same line, if any.
        position: Option<Position>,
    },
    /// `Resend: N` (or `rs N`): the printer wants line `N` again.
    Resend(u64),
    /// `echo:busy: processing` and the like: still working on a long command.
    Busy,
    /// `wait`: idle, waiting for commands.
    Wait,
    /// Stock Marlin's `M114` line, `X:… Y:… Z:… E:… Count …`.
    Position(Position),
    /// `Error:…` or `!! …`: what went wrong with a command (a transmission error is followed by
    /// a [`Reply::Resend`]).
    Error(String),
    /// The printer stopped itself (`kill()`, "Printer halted"): it answers nothing more until
    /// reset.
    Halted(String),
    /// `start`: the board booted.
    Start,
    /// Anything else: `echo:` lines, temperature reports, unknown-command notices, boot noise.
    Other,
}

impl Reply {
    /// What `line` (without its line ending) means.
    ///
    /// ```
    /// use yarok_hw::marlin::{Position, Reply};
    ///
    /// assert_eq!(Reply::parse("Resend: 12"), Reply::Resend(12));
    /// assert_eq!(
    ///     Reply::parse("X:10.00 Y:-2.50 Z:5.00 E:0.00 Count X:800 Y:-200 Z:2000"),
    ///     Reply::Position(Position { x: 10.0, y: -2.5, z: 5.0 })
    /// );
    /// assert_eq!(Reply::parse("ok T:21.30 /0.00 B:21.30 /0.00 @:0"), Reply::Ok { position: None });
    /// ```
    pub fn parse(line: &str) -> Reply {
        let line = line.trim();
        if let Some(rest) = strip_prefix_ignore_case(line, "ok")
            && (rest.is_empty() || rest.starts_with(' '))
        {
            return Reply::Ok {
                position: position(rest),
            };
        }
        if let Some(line) = resend(line) {
            return Reply::Resend(line);
        }
        let lower = line.to_ascii_lowercase();
        if lower.contains("kill() called") || lower.contains("printer halted") {
            return Reply::Halted(line.to_owned());
        }
        if let Some(message) = line
            .strip_prefix("Error:")
            .or_else(|| line.strip_prefix("!!"))
        {
            return Reply::Error(message.trim().to_owned());
        }
        if lower.starts_with("busy") || lower.starts_with("echo:busy") {
            return Reply::Busy;
        }
        match line {
            "wait" => return Reply::Wait,
            "start" => return Reply::Start,
            _ => {}
        }
        if line.starts_with("X:")
            && let Some(position) = position(line)
        {
            return Reply::Position(position);
        }
        Reply::Other
    }
}

/// `line` without `prefix`, compared without case.
fn strip_prefix_ignore_case<'a>(line: &'a str, prefix: &str) -> Option<&'a str> {
    let head = line.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| &line[prefix.len()..])
}

/// The line number of `Resend: N`, `Resend:N`, `rs N` or `rs N12`.
fn resend(line: &str) -> Option<u64> {
    let rest = strip_prefix_ignore_case(line, "resend")
        .or_else(|| strip_prefix_ignore_case(line, "rs"))?;
    let rest = rest.strip_prefix(':').unwrap_or(rest).trim_start();
    let rest = rest.strip_prefix('N').unwrap_or(rest);
    let digits: &str = &rest[..rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len())];
    digits.parse().ok()
}

/// The `X:`, `Y:` and `Z:` values of `text` before any `Count`, if all three are numbers.
fn position(text: &str) -> Option<Position> {
    let text = text.split("Count").next().unwrap_or(text);
    let axis = |name: &str| -> Option<f64> {
        let start = text.find(name)? + name.len();
        let rest = text[start..].trim_start();
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+'))
            .unwrap_or(rest.len());
        rest[..end].parse::<f64>().ok().filter(|v| v.is_finite())
    };
    Some(Position {
        x: axis("X:")?,
        y: axis("Y:")?,
        z: axis("Z:")?,
    })
}

#[cfg(test)]
mod tests {
    use super::{Position, Reply};

    #[test]
    fn every_reply_form_of_both_firmwares_is_understood() {
        let at = |x, y, z| Some(Position { x, y, z });
        for (line, expected) in [
            ("ok", Reply::Ok { position: None }),
            ("ok N12 P15 B3", Reply::Ok { position: None }),
            (
                "ok X:10.0 Y:10.0 Z:5.0 E:0 Count: A:1000 B:1000 C:500",
                Reply::Ok {
                    position: at(10.0, 10.0, 5.0),
                },
            ),
            (
                "X:110.00 Y:110.00 Z:0.50 E:0.00 Count X:8800 Y:8800 Z:104",
                Reply::Position(Position {
                    x: 110.0,
                    y: 110.0,
                    z: 0.5,
                }),
            ),
            ("Resend: 5", Reply::Resend(5)),
            ("Resend:4", Reply::Resend(4)),
            ("rs N7", Reply::Resend(7)),
            ("echo:busy: processing", Reply::Busy),
            ("busy:processing", Reply::Busy),
            ("wait", Reply::Wait),
            ("start", Reply::Start),
            (
                "Error:checksum mismatch, Last Line: 3",
                Reply::Error("checksum mismatch, Last Line: 3".into()),
            ),
            (
                "!! Move out of range",
                Reply::Error("Move out of range".into()),
            ),
            (
                "Error:Printer halted. kill() called!",
                Reply::Halted("Error:Printer halted. kill() called!".into()),
            ),
            (" T:210.08 /210.00 B:55.02 /55.00 @:74 B@:32", Reply::Other),
            ("echo:Unknown command: \"M204\"", Reply::Other),
            ("// Unknown command:\"M204\"", Reply::Other),
            ("okay then", Reply::Other),
            ("X:nan Y:1 Z:2", Reply::Other),
        ] {
            assert_eq!(Reply::parse(line), expected, "{line:?}");
        }
    }
}
