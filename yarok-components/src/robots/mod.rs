//! Robots.

use std::cell::RefCell;
use std::rc::Rc;

use yarok_core::compose::{Component, Declaration};
use yarok_core::runtime::{Bind, RuntimeError};
use yarok_mjc::{ActuatorId, Data, SensorId, SimBind};

/// The work volume of the [`AnetA30`], in millimetres.
pub const WORK_VOLUME_MM: [f64; 3] = [320.0, 320.0, 420.0];

/// How close (sum of the axes' distances, millimetres) counts as arrived for [`AnetA30::is_at`].
pub const ARRIVED_MM: f64 = 0.25;

/// A 3-D printer used as a cartesian robot: its head moves to `[x, y, z]` millimetres inside a
/// 320 × 320 × 420 mm work volume (targets outside are clamped to it). Tools attach to the body
/// `head` (`<cam name="cam" parent="head"/>` inside the tag).
///
/// Tag `anet_a30`; config `stiffness` (N/m of the axes' position servos, default 2000).
///
/// Environments: `sim` drives three position servos in MuJoCo; `mock` moves instantly.
#[derive(Clone)]
pub struct AnetA30 {
    interface: Rc<RefCell<dyn PrinterInterface>>,
}

impl std::fmt::Debug for AnetA30 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AnetA30").field("at", &self.at()).finish()
    }
}

trait PrinterInterface {
    fn move_to(&mut self, target_mm: [f64; 3]);
    fn at(&self) -> [f64; 3];
}

impl AnetA30 {
    /// Starts moving the head to `target` (millimetres), clamped to the work volume; returns the
    /// clamped target.
    ///
    /// A NaN coordinate is a warning (`tracing`) and goes to 0; an infinite one to the end of
    /// its axis.
    pub fn move_to(&self, target: [f64; 3]) -> [f64; 3] {
        if target.iter().any(|t| t.is_nan()) {
            tracing::warn!("printer: move_to({target:?}) has a NaN coordinate; it goes to 0");
        }
        let clamped = clamp(target);
        self.interface.borrow_mut().move_to(clamped);
        clamped
    }

    /// Where the head is, in millimetres.
    pub fn at(&self) -> [f64; 3] {
        self.interface.borrow().at()
    }

    /// Whether the head is at `target` (clamped to the work volume) within [`ARRIVED_MM`].
    pub fn is_at(&self, target: [f64; 3]) -> bool {
        let at = self.at();
        clamp(target)
            .iter()
            .zip(at)
            .map(|(t, a)| (t - a).abs())
            .sum::<f64>()
            < ARRIVED_MM
    }
}

fn clamp(target: [f64; 3]) -> [f64; 3] {
    let mut clamped = [0.0; 3];
    for ((c, t), max) in clamped.iter_mut().zip(target).zip(WORK_VOLUME_MM) {
        *c = if t.is_nan() { 0.0 } else { t.clamp(0.0, max) };
    }
    clamped
}

impl Component for AnetA30 {
    fn declaration() -> Declaration {
        Declaration::new("anet_a30")
            .default("stiffness", 2000.0)
            .template(include_str!("anet_a30.xml"))
    }

    fn bind(bind: &mut Bind<'_>) -> Result<Self, RuntimeError> {
        let interface: Rc<RefCell<dyn PrinterInterface>> = match bind.environment() {
            "sim" => {
                let [x, y, z] = ["x", "y", "z"];
                Rc::new(RefCell::new(SimPrinter {
                    data: bind.sim()?.data(),
                    actuators: [
                        bind.actuator_id(x)?,
                        bind.actuator_id(y)?,
                        bind.actuator_id(z)?,
                    ],
                    sensors: [bind.sensor_id(x)?, bind.sensor_id(y)?, bind.sensor_id(z)?],
                }))
            }
            "mock" => Rc::new(RefCell::new(MockPrinter { at: [0.0; 3] })),
            _ => return Err(bind.no_interface()),
        };
        Ok(AnetA30 { interface })
    }
}

struct SimPrinter {
    data: Rc<RefCell<Data>>,
    actuators: [ActuatorId; 3],
    sensors: [SensorId; 3],
}

impl PrinterInterface for SimPrinter {
    fn move_to(&mut self, target_mm: [f64; 3]) {
        let mut data = self.data.borrow_mut();
        for (actuator, mm) in self.actuators.iter().zip(target_mm) {
            data.set_ctrl(*actuator, mm / 1000.0);
        }
    }

    fn at(&self) -> [f64; 3] {
        let data = self.data.borrow();
        self.sensors.map(|sensor| data.sensor(sensor)[0] * 1000.0)
    }
}

struct MockPrinter {
    at: [f64; 3],
}

impl PrinterInterface for MockPrinter {
    fn move_to(&mut self, target_mm: [f64; 3]) {
        self.at = target_mm;
    }

    fn at(&self) -> [f64; 3] {
        self.at
    }
}
