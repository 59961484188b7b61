//! A `real`-style component for lifecycle tests: its async bind connects to a TCP server on
//! loopback, spawns a reader task, and registers a stop action that sends `STOP`.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::rc::Rc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::io::{AsyncBufReadExt, AsyncWriteExt};
use tokio::sync::Notify;
use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, MockBackend,
};

/// A lab bench: hardware-like (paced ticks), no physics.
pub(crate) struct Lab;
impl Environment for Lab {
    const NAME: &'static str = "lab";
    type Backend = MockBackend;
}

#[derive(serde::Deserialize)]
struct DeviceSettings {
    port: u16,
    #[serde(default)]
    refuse_to_stop: bool,
}

/// A device's handle: the lines it has received.
#[derive(Clone)]
pub(crate) struct Device {
    lines: Rc<RefCell<VecDeque<String>>>,
    arrived: Rc<Notify>,
}

impl Device {
    /// The next line from the device, as soon as it arrives.
    pub(crate) async fn next_line(&self) -> String {
        loop {
            if let Some(line) = self.lines.borrow_mut().pop_front() {
                return line;
            }
            self.arrived.notified().await;
        }
    }
}

impl Component for Device {
    fn declaration() -> Declaration {
        Declaration::new("device").template("<mujoco/>")
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces.add::<Lab>();
    }
}

impl Interface<Lab> for Device {
    async fn bind(bind: &mut Bind<Lab>) -> Result<Self, BindError> {
        let settings: DeviceSettings = bind.settings()?;
        let connect = tokio::net::TcpStream::connect(("127.0.0.1", settings.port));
        let stream = bind
            .within(5.0, "connecting", connect)
            .await?
            .map_err(|e| bind.error(e))?;
        let (reader, mut writer) = stream.into_split();
        let device = Device {
            lines: Rc::default(),
            arrived: Rc::default(),
        };
        let (lines, arrived) = (Rc::clone(&device.lines), Rc::clone(&device.arrived));
        bind.spawn(async move {
            let mut reader = tokio::io::BufReader::new(reader).lines();
            while let Some(line) = reader.next_line().await? {
                lines.borrow_mut().push_back(line);
                arrived.notify_one();
            }
            Ok(())
        });
        bind.on_stop_within(2.0, async move {
            writer.write_all(b"STOP\n").await?;
            writer.flush().await?;
            if settings.refuse_to_stop {
                return Err("the device refused to stop".into());
            }
            Ok(())
        });
        Ok(device)
    }
}

/// A loopback server that records every line it receives, optionally greeting each client
/// with `PING` after a delay.
pub(crate) struct Server {
    port: u16,
    received: Arc<Mutex<Vec<String>>>,
}

impl Server {
    pub(crate) fn start(ping_after: Option<Duration>) -> Server {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = listener.local_addr().unwrap().port();
        let received = Arc::new(Mutex::new(Vec::new()));
        let log = Arc::clone(&received);
        std::thread::spawn(move || {
            for stream in listener.incoming() {
                let Ok(mut stream) = stream else { return };
                let log = Arc::clone(&log);
                std::thread::spawn(move || {
                    if let Some(delay) = ping_after {
                        std::thread::sleep(delay);
                        let _client_may_be_gone = stream.write_all(b"PING\n");
                    }
                    for line in BufReader::new(stream).lines() {
                        let Ok(line) = line else { return };
                        log.lock().unwrap().push(line);
                    }
                });
            }
        });
        Server { port, received }
    }

    pub(crate) fn port(&self) -> u16 {
        self.port
    }

    /// Waits (up to 5 s) until `count` lines have arrived, and returns them all.
    pub(crate) fn received(&self, count: usize) -> Vec<String> {
        let started = Instant::now();
        while self.received.lock().unwrap().len() < count && started.elapsed().as_secs() < 5 {
            std::thread::sleep(Duration::from_millis(5));
        }
        self.received.lock().unwrap().clone()
    }
}
