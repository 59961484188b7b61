//! [`Viewer`]: a window with the live scene, the simulation paced to the wall clock.

use std::time::{Duration, Instant};

use yarok_core::BoxError;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::{
    Button, Corner, Key, Overlay, RenderPreset, SimBackend, View, Visual, WindowEvent,
};

/// The most frames a second the window is drawn.
const FRAME_RATE: f64 = 60.0;

/// Frames a second while the simulation is behind the wall clock.
const BEHIND_FRAME_RATE: f64 = 4.0;

/// How long a paused viewer sleeps between looks at its window.
const PAUSED_NAP: Duration = Duration::from_millis(10);

const HELP: &str = "Space\nRight\nBackspace\n+ / -\nTab\nC / F / T\nS\nH or F1\nLeft drag\nRight drag\nWheel, middle drag\nClose the window";
const HELP_WHAT: &str = "pause, resume\nstep (paused)\nback to the start\nfaster, slower\nnext camera\ncontacts, forces, frames\ncameras and sensors, with frames\nthis help\norbit\npan\nzoom\nend the run";

/// How a [`Viewer`] looks (`[plugins.viewer]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ViewerSettings {
    /// Width and height of the window.
    pub size: [u32; 2],
    /// Shadows and reflections; by default only on a GPU (software OpenGL draws a frame
    /// several times faster without).
    pub quality: Option<bool>,
    /// Platform seconds per wall-clock second at the start (`+`/`-` double and halve it).
    pub speed: f64,
    /// Start paused.
    pub paused: bool,
    /// Without an X server, run on without a window (paced all the same) instead of failing.
    pub headless: bool,
    /// Keep the window open once the behaviours have ended, the world as they left it (the
    /// camera still moves), until it is closed or Ctrl-C.
    pub keep_open: bool,
}

impl Default for ViewerSettings {
    fn default() -> Self {
        Self {
            size: [800, 600],
            quality: None,
            speed: 1.0,
            paused: false,
            headless: false,
            keep_open: false,
        }
    }
}

/// A window with the live scene of a `sim` run. Passive: it draws the current state at most
/// 60 times a second and paces the simulation to the wall clock (times `speed`), never slower;
/// the mouse orbits, pans and zooms the free camera; keys pause, resume, step and put the world
/// back to its start state ([`World::restart`]), change its speed, switch between the free
/// camera and the model's cameras and show contacts, forces, frames, and the cameras and
/// tactile sensors' cameras with their frames (`H` lists them).
/// Closing the window ends the run. The window's title says the platform time and whether it is
/// paused. With `keep_open`, the window stays open once the behaviours have ended (its title
/// says `ended`), showing the world as they left it, until it is closed or Ctrl-C.
///
/// Registered by `yarok::platform()` (feature `viewer`) as `viewer`; `yarok run WORLD
/// --viewer` adds it.
#[derive(Debug)]
pub struct Viewer {
    settings: ViewerSettings,
    view: Option<View>,
    paused: bool,
    speed: f64,
    help: bool,
    /// A single step asked for while paused.
    stepping: bool,
    /// The wall-clock instant and platform time that pacing counts from.
    anchor: Option<(Instant, f64)>,
    last_frame: Option<Instant>,
    /// The button held and where the pointer was.
    drag: Option<(Button, f64, f64)>,
    closed: bool,
    /// The run has ended: the window shows the world as it was left.
    ended: bool,
    /// Time spent drawing, and frames drawn.
    drawing: Duration,
    frames: u64,
}

impl Viewer {
    /// A viewer with these settings; the window opens when the run starts.
    ///
    /// # Errors
    ///
    /// When `speed` is not a positive number or the size has a zero side.
    pub fn new(settings: ViewerSettings) -> Result<Self, BoxError> {
        if !(settings.speed > 0.0 && settings.speed.is_finite()) {
            return Err(format!("`speed` {} must be above 0", settings.speed).into());
        }
        if settings.size.contains(&0) {
            return Err(format!("`size` {:?} has a zero side", settings.size).into());
        }
        Ok(Self {
            paused: settings.paused,
            speed: settings.speed,
            settings,
            view: None,
            help: false,
            stepping: false,
            anchor: None,
            last_frame: None,
            drag: None,
            closed: false,
            ended: false,
            drawing: Duration::ZERO,
            frames: 0,
        })
    }

    /// The wall-clock time spent drawing so far, and the frames drawn.
    pub fn drawing(&self) -> (Duration, u64) {
        (self.drawing, self.frames)
    }

    /// Handles the window's events; whether the world went back to its start.
    fn handle_events(&mut self, world: &World<'_>) -> Result<bool, BoxError> {
        let Some(view) = &mut self.view else {
            return Ok(false);
        };
        let mut reset = false;
        for event in view.events() {
            match event {
                WindowEvent::Close => self.closed = true,
                WindowEvent::Key(
                    Key::Space | Key::Right | Key::Backspace | Key::Char('+' | '=' | '-'),
                ) if self.ended => {}
                WindowEvent::Key(key) => match key {
                    Key::Space => {
                        self.paused = !self.paused;
                        self.anchor = None;
                    }
                    Key::Right => self.stepping = self.paused,
                    Key::Backspace => reset = true,
                    Key::Char('+' | '=') => {
                        self.speed *= 2.0;
                        self.anchor = None;
                    }
                    Key::Char('-') => {
                        self.speed /= 2.0;
                        self.anchor = None;
                    }
                    Key::Tab => view.next_camera(),
                    Key::Char('c') => {
                        view.toggle(Visual::Contacts);
                    }
                    Key::Char('f') => {
                        view.toggle(Visual::Forces);
                    }
                    Key::Char('t') => {
                        view.toggle(Visual::Frames);
                    }
                    Key::Char('s') => {
                        view.toggle(Visual::Cameras);
                    }
                    Key::Char('h') | Key::F1 => self.help = !self.help,
                    _ => {}
                },
                WindowEvent::Press(button, x, y) => self.drag = Some((button, x, y)),
                WindowEvent::Release(_) => self.drag = None,
                WindowEvent::Motion(x, y) => {
                    if let Some((button, from_x, from_y)) = self.drag {
                        let (dx, dy) = (x - from_x, y - from_y);
                        match button {
                            Button::Left => view.orbit(dx, dy),
                            Button::Right => view.pan(dx, dy),
                            Button::Middle => view.zoom(-dy / 10.0),
                        }
                        self.drag = Some((button, x, y));
                    }
                }
                WindowEvent::Scroll(steps) => view.zoom(steps),
                _ => {}
            }
        }
        if reset {
            world.restart()?;
            self.anchor = None;
        }
        Ok(reset)
    }

    /// Draws the scene if a frame is due: `FRAME_RATE` times a second at most, and less often
    /// than `every` only when asked (`every` zero: whenever a frame is due).
    fn draw(&mut self, sim: &SimBackend, time: f64, every: Duration) -> Result<(), BoxError> {
        let Some(view) = &mut self.view else {
            return Ok(());
        };
        let now = Instant::now();
        let wait = every.max(Duration::from_secs_f64(1.0 / FRAME_RATE));
        if self
            .last_frame
            .is_some_and(|last| now.duration_since(last) < wait)
        {
            return Ok(());
        }
        self.last_frame = Some(now);
        let state = if self.ended {
            "  ended"
        } else if self.paused {
            "  paused"
        } else {
            ""
        };
        let status = format!(
            "{time:.2} s\nx{}{state}\n{}",
            self.speed,
            view.camera_name()
        );
        let mut overlays = vec![Overlay {
            corner: Corner::BottomLeft,
            left: "time\nspeed\ncamera",
            right: &status,
        }];
        if self.help {
            overlays.push(Overlay {
                corner: Corner::TopLeft,
                left: HELP,
                right: HELP_WHAT,
            });
        }
        view.draw(&mut sim.data_mut(), &overlays)?;
        view.window()
            .set_title(&format!("yarok - t = {time:.2} s{state}"));
        self.drawing += now.elapsed();
        self.frames += 1;
        Ok(())
    }

    /// Waits until the wall clock catches up with platform time (times the speed), drawing
    /// and handling events meanwhile; while paused, until resumed or stepped. A simulation
    /// behind the wall clock is not slowed further by drawing: it is drawn then only
    /// `BEHIND_FRAME_RATE` times a second.
    fn pace(&mut self, world: &World<'_>, sim: &SimBackend, time: f64) -> Result<(), BoxError> {
        loop {
            if self.handle_events(world)? {
                return Ok(());
            }
            if self.closed {
                return Ok(());
            }
            if self.paused {
                self.draw(sim, time, Duration::ZERO)?;
                if std::mem::take(&mut self.stepping) {
                    return Ok(());
                }
                std::thread::sleep(PAUSED_NAP);
                continue;
            }
            let (wall, from) = *self.anchor.get_or_insert((Instant::now(), time));
            let due = wall + Duration::from_secs_f64(((time - from) / self.speed).max(0.0));
            if Instant::now() >= due {
                return self.draw(sim, time, Duration::from_secs_f64(1.0 / BEHIND_FRAME_RATE));
            }
            self.draw(sim, time, Duration::ZERO)?;
            let now = Instant::now();
            let next_frame = self
                .last_frame
                .map_or(now, |last| last + Duration::from_secs_f64(1.0 / FRAME_RATE));
            if now < due {
                std::thread::sleep(due.min(next_frame.max(now)) - now);
            }
            if Instant::now() >= due {
                return Ok(());
            }
        }
    }
}

impl Plugin for Viewer {
    fn name(&self) -> String {
        "viewer".into()
    }

    fn environments(&self) -> Vec<&'static str> {
        super::only_sim()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let sim = super::sim_backend(world)?;
        let [width, height] = self.settings.size;
        let preset = self.settings.quality.map(|quality| {
            if quality {
                RenderPreset::Quality
            } else {
                RenderPreset::Fast
            }
        });
        match View::open(sim.model(), "yarok", (width, height), preset) {
            Ok(view) => self.view = Some(view),
            Err(yarok_mjc::RenderError::NoDisplay {
                display: x_display,
                reason,
            }) if self.settings.headless => {
                tracing::warn!(display = %x_display, %reason, "no window for the viewer; running on without");
            }
            Err(error) => return Err(error.into()),
        }
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let sim = super::sim_backend(world)?;
        let time = sim.data().time();
        self.pace(world, sim, time)?;
        if self.closed {
            world.pl().stop();
        }
        Ok(())
    }

    fn end(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        if !self.settings.keep_open || self.view.is_none() {
            return Ok(());
        }
        let sim = super::sim_backend(world)?;
        let time = sim.data().time();
        self.ended = true;
        while !self.closed && !world.pl().stop_requested() {
            self.handle_events(world)?;
            self.draw(sim, time, Duration::ZERO)?;
            std::thread::sleep(PAUSED_NAP);
        }
        Ok(())
    }
}
