//! [`Tactile`]: the component over a [`TactileSensor`] for one kind of sensor.

use std::marker::PhantomData;

use serde::Serialize;
use serde::de::DeserializeOwned;
use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Interfaces, Mock};

use super::kind::{SensorKind, check_geometry};
use super::sensor::TactileSensor;

/// One kind of camera-based tactile sensor: its name, and the geometry and optics its
/// template and model share. Implemented by [`DigitKind`](super::DigitKind),
/// [`GelSight2014Kind`](super::GelSight2014Kind) and [`GelTipKind`](super::GelTipKind).
pub trait TactileKind: Clone + std::fmt::Debug + 'static {
    /// The name messages give the sensor's type (`Digit`).
    const NAME: &'static str;
    /// The gel's and the camera's geometry its optical model is made for.
    #[doc(hidden)]
    type Geometry: Serialize + DeserializeOwned + PartialEq;
    /// Its declaration, image, gel and optics.
    #[doc(hidden)]
    fn kind() -> &'static dyn SensorKind;
    /// The geometry its optical model is made for.
    #[doc(hidden)]
    fn geometry() -> Self::Geometry;
}

/// A tactile sensor of kind `K` in the world: a [`TactileSensor`] (it derefs to one) with
/// `sim` and `mock` interfaces, and `real` with the `camera` feature. Its config (`pos`,
/// `quat`, `fps`, `noise`, `parallel`, `calibration`) is each kind's, as [`Digit`](super::Digit),
/// [`GelSight2014`](super::GelSight2014) and [`GelTip`](super::GelTip) say.
#[derive(Debug, Clone)]
pub struct Tactile<K>(TactileSensor, PhantomData<K>);

impl<K> std::ops::Deref for Tactile<K> {
    type Target = TactileSensor;

    fn deref(&self) -> &TactileSensor {
        &self.0
    }
}

impl<K: TactileKind> Tactile<K> {
    /// The sensor, once its config keeps the geometry its model is made for.
    fn checked<E: yarok_core::component::Environment>(
        bind: &mut Bind<E>,
        sensor: impl FnOnce(&mut Bind<E>) -> Result<TactileSensor, BindError>,
    ) -> Result<Self, BindError> {
        check_geometry(bind, &K::geometry())?;
        Ok(Self(sensor(bind)?, PhantomData))
    }
}

impl<K: TactileKind> Component for Tactile<K> {
    fn declaration() -> Declaration {
        K::kind().declaration()
    }

    fn interfaces(interfaces: &mut Interfaces<Self>) {
        #[cfg(feature = "render")]
        interfaces.add::<yarok_mjc::Sim>();
        #[cfg(not(feature = "render"))]
        interfaces.unavailable::<yarok_mjc::Sim>("the `render` feature");
        interfaces.add::<Mock>();
        #[cfg(feature = "camera")]
        interfaces.add::<yarok_hw::Real>();
        #[cfg(not(feature = "camera"))]
        interfaces.unavailable::<yarok_hw::Real>("the `camera` feature");
    }

    fn type_name() -> &'static str {
        K::NAME
    }
}

#[cfg(feature = "camera")]
impl<K: TactileKind> Interface<yarok_hw::Real> for Tactile<K> {
    fn check(bind: &Bind<yarok_hw::Real>) -> Result<(), BindError> {
        crate::cameras::real::check_settings(bind)
    }

    async fn bind(bind: &mut Bind<yarok_hw::Real>) -> Result<Self, BindError> {
        check_geometry(bind, &K::geometry())?;
        let sensor = TactileSensor::bind_real(K::kind(), bind).await?;
        Ok(Self(sensor, PhantomData))
    }
}

#[cfg(feature = "render")]
impl<K: TactileKind> Interface<yarok_mjc::Sim> for Tactile<K> {
    async fn bind(bind: &mut Bind<yarok_mjc::Sim>) -> Result<Self, BindError> {
        Self::checked(bind, |bind| TactileSensor::bind_sim(K::kind(), bind))
    }
}

impl<K: TactileKind> Interface<Mock> for Tactile<K> {
    async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
        Self::checked(bind, |bind| TactileSensor::bind_mock(K::kind(), bind))
    }
}
