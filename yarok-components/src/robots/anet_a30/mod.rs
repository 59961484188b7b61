//! [`AnetA30`]: a 3-D printer used as a cartesian robot.

mod drive;
mod exposed;
mod mock;
mod real;
mod sim;

use std::rc::Rc;

use yarok_core::component::{
    Bind, BindError, Component, Declaration, Environment, Interface, Interfaces, Mock,
};
use yarok_mjc::Sim;

pub use drive::AxesDrive;
use mock::MockAxes;
use sim::SimAxes;

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
/// Environments: `sim` drives three position servos in MuJoCo; `real` drives a Marlin printer
/// on a serial port (interface settings `port`, default `/dev/ttyUSB0`; `baud`, 115 200; `feed`,
/// mm/s, 50; `home`, whether to home at start, true; `boot_seconds`, 10): each newest target is
/// sent as a `G1`, its arrival awaited with `M400` and read back with `M114`, so [`AnetA30::at`]
/// is where the printer last said the head was and [`AnetA30::is_at`] turns true on arrival, and
/// the printer stops (`M410`) at shutdown; `mock` moves instantly.
#[derive(Clone)]
pub struct AnetA30 {
    axes: Rc<dyn AxesDrive>,
}

impl std::fmt::Debug for AnetA30 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AnetA30").field("at", &self.at()).finish()
    }
}

impl AnetA30 {
    /// A printer whose head `axes` move: for an environment of your own. It publishes its
    /// `state` (`at`) and takes `command`s (`{"move_to": [x, y, z]}`, mm) for any plugin.
    pub fn with_drive<E: Environment>(bind: &mut Bind<E>, axes: Rc<dyn AxesDrive>) -> Self {
        let printer = Self { axes };
        exposed::expose(bind, &printer);
        printer
    }

    /// Starts moving the head to `target` (millimetres), clamped to the work volume; returns the
    /// clamped target.
    ///
    /// A NaN coordinate is a warning (`tracing`) and goes to 0; an infinite one to the end of
    /// its axis.
    pub fn move_to(&self, target: [f64; 3]) -> [f64; 3] {
        let clamped = requested("move_to", target);
        self.axes.move_to(clamped);
        clamped
    }

    /// Puts the head at `target` (millimetres, clamped to the work volume) at once and at rest,
    /// and holds it there; returns the clamped target. In `sim` the axes are set rather than
    /// driven, so where the head is afterwards does not depend on earlier moves: for setting a
    /// scene up, or collecting data that must not depend on the order it is collected in.
    /// `mock` as [`AnetA30::move_to`].
    pub fn place(&self, target: [f64; 3]) -> [f64; 3] {
        let clamped = requested("place", target);
        self.axes.place(clamped);
        clamped
    }

    /// Where the head is, in millimetres.
    pub fn at(&self) -> [f64; 3] {
        self.axes.at()
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

/// A target given to `request`, clamped to the work volume; a NaN coordinate is a warning.
fn requested(request: &str, target: [f64; 3]) -> [f64; 3] {
    if target.iter().any(|t| t.is_nan()) {
        tracing::warn!("printer: {request}({target:?}) has a NaN coordinate; it goes to 0");
    }
    clamp(target)
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

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        interfaces
            .add::<Sim>()
            .add::<yarok_hw::Real>()
            .add::<Mock>();
    }
}

impl Interface<Sim> for AnetA30 {
    async fn bind(bind: &mut Bind<Sim>) -> Result<Self, BindError> {
        let axes = Rc::new(SimAxes::bind(bind)?);
        Ok(Self::with_drive(bind, axes))
    }
}

impl Interface<Mock> for AnetA30 {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Ok(Self::with_drive(bind, Rc::new(MockAxes::default())))
    }
}
