//! The reply parser over 100 000 generated lines — fragments of every reply form, numbers,
//! signs, separators and arbitrary bytes mixed — never panics, and what it understands is
//! consistent with the line.

use yarok_hw::marlin::Reply;

use yarok_test::generator;

use generator::Generator;

/// Marlin-like lines from the generator.
trait Lines {
    fn number(&mut self) -> String;
    fn line(&mut self) -> String;
}

impl Lines for Generator {
    /// A number as a printer might print it, or something almost like one.
    fn number(&mut self) -> String {
        let value = (self.next_u64() % 200_000) as f64 / 100.0 - 1000.0;
        match self.next_u64() % 4 {
            0 => format!("{value:.2}"),
            1 => format!("{value}"),
            2 => format!("{}", value as i64),
            _ => self.pick(&["-", ".", "1e", "", "--1"]).to_owned(),
        }
    }

    fn line(&mut self) -> String {
        if self.next_u64().is_multiple_of(5) {
            // A position report in either firmware's form, possibly cut short.
            let ok = if self.next_u64().is_multiple_of(2) {
                "ok "
            } else {
                ""
            };
            let line = format!(
                "{ok}X:{} Y:{} Z:{} E:0.00 Count X:{} Y:1 Z:2",
                self.number(),
                self.number(),
                self.number(),
                self.number()
            );
            let cut = (self.next_u64() as usize % (line.len() + 1)).max(line.len() / 2);
            return line[..cut].to_owned();
        }
        const PIECES: &[&str] = &[
            "ok",
            "ok ",
            "OK",
            "X:",
            "Y:",
            "Z:",
            "E:",
            "Count",
            " Count X:",
            "Resend:",
            "Resend: ",
            "rs ",
            "N",
            "echo:",
            "busy:",
            " processing",
            "wait",
            "start",
            "Error:",
            "!!",
            "kill() called!",
            "Printer halted",
            "T:",
            " /",
            "B:",
            "@:",
            "-",
            "+",
            ".",
            "..",
            " ",
            "\t",
            "\r",
            "0",
            "1",
            "9",
            "12.5",
            "-0.00",
            "99999999999999999999999",
            "1e309",
            "NaN",
            "inf",
            "é",
            "\u{fffd}",
            "*",
            ";",
            "\"",
        ];
        let mut line = String::new();
        for _ in 0..self.next_u64() % 12 {
            if self.next_u64().is_multiple_of(10) {
                // Arbitrary bytes, decoded as the driver decodes them.
                let bytes: Vec<u8> = (0..self.next_u64() % 6)
                    .map(|_| self.next_u64() as u8)
                    .collect();
                line.push_str(&String::from_utf8_lossy(&bytes));
            } else {
                line.push_str(self.pick(PIECES));
            }
        }
        line
    }
}

#[test]
fn a_hundred_thousand_generated_lines_parse_without_panic() {
    let mut lines = Generator(0x9E37_79B9_7F4A_7C15);
    let mut understood = [0usize; 4];
    for _ in 0..100_000 {
        let line = lines.line();
        match Reply::parse(&line) {
            Reply::Ok { position } => {
                understood[0] += 1;
                assert!(
                    line.trim().to_ascii_lowercase().starts_with("ok"),
                    "{line:?}"
                );
                if let Some(p) = position {
                    assert!(
                        p.x.is_finite() && p.y.is_finite() && p.z.is_finite(),
                        "{line:?}"
                    );
                }
            }
            Reply::Resend(_) => {
                understood[1] += 1;
                let lower = line.trim().to_ascii_lowercase();
                assert!(
                    lower.starts_with("resend") || lower.starts_with("rs"),
                    "{line:?}"
                );
            }
            Reply::Position(p) => {
                understood[2] += 1;
                assert!(
                    p.x.is_finite() && p.y.is_finite() && p.z.is_finite(),
                    "{line:?}"
                );
            }
            _ => understood[3] += 1,
        }
    }
    // The generator reaches every kind of reply, so the checks above are exercised.
    assert!(understood.iter().all(|n| *n > 50), "{understood:?}");
}
