//! OctoPrint's VirtualPrinter on a pseudo-terminal, through `scripts/peers/virtual_printer_bridge.py`
//! (installed by `scripts/setup-test-peers.sh`), for tests: shared by yarok-hw's tests and the
//! workspace's.
#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use yarok_hw::SerialPort;
use yarok_hw::marlin::{Marlin, MarlinSettings};

/// The bridge script: in the workspace's `scripts/peers`, above whichever crate's tests run.
fn bridge() -> PathBuf {
    let script = "scripts/peers/virtual_printer_bridge.py";
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .map(|folder| folder.join(script))
        .find(|path| path.is_file())
        .unwrap_or_else(|| panic!("{script} not found above {}", env!("CARGO_MANIFEST_DIR")))
}

/// The VirtualPrinter behind a pseudo-terminal, stopped when dropped.
pub(crate) struct VirtualPrinter {
    bridge: Child,
    pub(crate) path: String,
}

impl VirtualPrinter {
    /// Starts one with these settings (JSON) over the plugin's defaults.
    pub(crate) fn start(settings: &str) -> Self {
        let peers = std::env::var_os("YAROK_CACHE_DIR")
            .map(PathBuf::from)
            .or_else(|| {
                std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache/yarok"))
            })
            .expect("YAROK_CACHE_DIR or HOME")
            .join("peers/bin/python");
        assert!(
            peers.exists(),
            "{} is missing: run `bash scripts/setup-test-peers.sh` (scripts/test.sh does)",
            peers.display()
        );
        let bridge = bridge();
        let mut bridge = Command::new(peers)
            .arg(bridge)
            .arg(settings)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("the bridge starts");
        let mut path = String::new();
        BufReader::new(bridge.stdout.take().expect("its output"))
            .read_line(&mut path)
            .expect("the bridge names its device");
        Self {
            bridge,
            path: path.trim().to_owned(),
        }
    }

    pub(crate) async fn connect(&self) -> Marlin<SerialPort> {
        let mut settings = MarlinSettings::new(self.path.clone());
        settings.boot_quiet = Duration::from_millis(300);
        settings.silence = Duration::from_secs(2);
        let port = SerialPort::open(&self.path, 115_200).expect("the device opens");
        Marlin::connect(port, settings)
            .await
            .expect("the printer answers")
    }
}

impl Drop for VirtualPrinter {
    fn drop(&mut self) {
        let _ = self.bridge.kill();
        let _ = self.bridge.wait();
    }
}
