//! OctoPrint's VirtualPrinter on a pseudo-terminal, through `scripts/peers/virtual_printer_bridge.py`
//! (installed by `scripts/setup-test-peers.sh`), for tests: shared by yarok-hw's tests and the
//! workspace's.

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use yarok_hw::SerialPort;
use yarok_hw::marlin::{Marlin, MarlinSettings};

use crate::peers;

/// The VirtualPrinter behind a pseudo-terminal, stopped when dropped.
#[derive(Debug)]
pub struct VirtualPrinter {
    bridge: Child,
    input: Mutex<ChildStdin>,
    /// A stable link to the device, as `/dev/serial/by-id/` names are.
    pub path: String,
    /// What the bridge reported after the path: received lines (`> …`) and events.
    reports: Arc<Mutex<Vec<String>>>,
}

impl VirtualPrinter {
    /// Starts one with these settings (JSON) over the plugin's defaults.
    pub fn start(settings: &str) -> Self {
        Self::launch(&[settings])
    }

    /// Starts one that comes back `seconds` after it drops the connection, as a printer whose
    /// USB cable is unplugged and plugged back in.
    pub fn replugging(settings: &str, seconds: f64) -> Self {
        Self::launch(&[settings, &seconds.to_string()])
    }

    fn launch(arguments: &[&str]) -> Self {
        let mut bridge = Command::new(peers::python())
            .arg(peers::script("virtual_printer_bridge.py"))
            .args(arguments)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("the bridge starts");
        let mut lines = BufReader::new(bridge.stdout.take().expect("its output")).lines();
        let path = lines
            .next()
            .expect("the bridge names its device")
            .expect("its output reads");
        let input = Mutex::new(bridge.stdin.take().expect("its input"));
        let reports = Arc::new(Mutex::new(Vec::new()));
        let kept = Arc::clone(&reports);
        std::thread::spawn(move || {
            for line in lines.map_while(Result::ok) {
                kept.lock().unwrap().push(line);
            }
        });
        Self {
            bridge,
            input,
            path,
            reports,
        }
    }

    /// Sends `line` to the printer as if it came down the line (a `!!DEBUG:` fault), whatever
    /// the client is doing.
    pub fn inject(&self, line: &str) {
        let mut input = self.input.lock().unwrap();
        writeln!(input, "{line}").expect("the bridge takes the line");
        input.flush().expect("the bridge takes the line");
    }

    /// The lines the printer ignored while it booted.
    pub fn ignored(&self) -> Vec<String> {
        self.lines_reported("~ ")
    }

    /// The lines the printer has received so far.
    pub fn received(&self) -> Vec<String> {
        self.lines_reported("> ")
    }

    /// The lines the bridge reported after `prefix`.
    fn lines_reported(&self, prefix: &str) -> Vec<String> {
        let reports = self.reports.lock().unwrap();
        let lines = reports
            .iter()
            .filter_map(|report| report.strip_prefix(prefix));
        lines.map(str::to_owned).collect()
    }

    /// Waits up to `limit` for the bridge to report `event` (`closed`, `dropped`,
    /// `replugged`); whether it did.
    pub fn saw(&self, event: &str, limit: Duration) -> bool {
        let until = Instant::now() + limit;
        loop {
            if self
                .reports
                .lock()
                .unwrap()
                .iter()
                .any(|report| report == event)
            {
                return true;
            }
            if Instant::now() >= until {
                return false;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Yarok's Marlin driver, connected to it at 250000 baud.
    pub async fn connect(&self) -> Marlin<SerialPort> {
        let port = SerialPort::open(&self.path, 250_000).expect("the device opens");
        Marlin::connect(port, self.settings())
            .await
            .expect("the printer answers")
    }

    /// The driver's settings for it: quick to boot, quick to call it silent.
    pub fn settings(&self) -> MarlinSettings {
        let mut settings = MarlinSettings::new(self.path.clone());
        settings.boot_quiet = Duration::from_millis(300);
        settings.silence = Duration::from_secs(2);
        settings
    }
}

impl Drop for VirtualPrinter {
    fn drop(&mut self) {
        let _ = self.bridge.kill();
        let _ = self.bridge.wait();
    }
}
