//! [`StatusLine`]: how a run is going, on one line of the terminal.

use std::io::Write;
use std::time::{Duration, Instant};

use yarok_core::BoxError;
use yarok_core::runtime::{Plugin, World};

/// How often the line is redrawn.
const EVERY: Duration = Duration::from_millis(250);

/// Shows on standard error, redrawn four times a second: platform time, how many times faster
/// than real time it advances, and ticks per second (over the last quarter second). Meant for a
/// terminal: `yarok run` adds it when standard error is one.
#[derive(Debug, Default)]
pub struct StatusLine {
    /// When the line was last drawn, and the platform's time and ticks then.
    last: Option<(Instant, f64, u64)>,
    drawn: bool,
}

impl StatusLine {
    /// A status line, first drawn a quarter second into the run.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Plugin for StatusLine {
    fn name(&self) -> String {
        "status line".into()
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let now = Instant::now();
        let (time, ticks) = (world.pl().time(), world.pl().ticks());
        let Some((then, time_then, ticks_then)) = self.last else {
            self.last = Some((now, time, ticks));
            return Ok(());
        };
        let wall = now.duration_since(then);
        if wall < EVERY {
            return Ok(());
        }
        let wall = wall.as_secs_f64();
        let mut line = std::io::stderr().lock();
        // A terminal that went away is no reason to stop the run.
        let _ = write!(
            line,
            "\r\x1b[Kt = {time:.2} s   ×{:.1} real time   {:.0} ticks/s",
            (time - time_then) / wall,
            (ticks - ticks_then) as f64 / wall
        );
        let _ = line.flush();
        self.drawn = true;
        self.last = Some((now, time, ticks));
        Ok(())
    }

    fn end(&mut self, _: &World<'_>) -> Result<(), BoxError> {
        if self.drawn {
            eprintln!();
        }
        Ok(())
    }
}
