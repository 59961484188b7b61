//! [`Interface`]: how a component binds in one environment; [`Interfaces`]: the ones it has.

use std::any::Any;
use std::future::Future;
use std::marker::PhantomData;
use std::pin::Pin;

use super::{Bind, BindContext, BindError, Component, Environment};

/// A component's interface in the environment `E`: how it makes its handle from what `E`'s
/// backend offers.
///
/// `bind` runs once at start-up, inside the platform's runtime, children before parents. It may
/// await (connect, handshake — bound each wait with [`Bind::within`]), register per-tick work
/// ([`Bind::on_tick`]), spawn tasks that live as long as the run ([`Bind::spawn`]) and register
/// a stop action that leaves the device safe at shutdown ([`Bind::on_stop`]).
///
/// See the [module documentation](super) for an example.
pub trait Interface<E: Environment>: Component {
    /// Makes the component's handle in environment `E`.
    ///
    /// # Errors
    ///
    /// [`BindError`] naming the component: an unknown name in its template, bad settings, a
    /// device that does not answer; the platform then stops without running behaviours.
    fn bind(bind: &mut Bind<E>) -> impl Future<Output = Result<Self, BindError>>;

    /// Finds what `bind` would refuse without touching any device: its settings. The platform
    /// checks every component before it binds the first, so that a typo in one device's
    /// settings is reported before another device is connected, activated or moved. Checks
    /// nothing unless overridden.
    ///
    /// ```
    /// use serde::Deserialize;
    /// use yarok_core::component::{Bind, BindError, Component, Declaration, Interface, Mock};
    ///
    /// #[derive(Deserialize, Default)]
    /// #[serde(default, deny_unknown_fields)]
    /// struct Settings {
    ///     port: String,
    /// }
    ///
    /// struct Printer;
    ///
    /// impl Component for Printer {
    ///     fn declaration() -> Declaration {
    ///         Declaration::new("printer")
    ///     }
    /// }
    ///
    /// impl Interface<Mock> for Printer {
    ///     async fn bind(bind: &mut Bind<Mock>) -> Result<Self, BindError> {
    ///         let _settings: Settings = bind.settings()?;
    ///         Ok(Printer)
    ///     }
    ///
    ///     fn check(bind: &Bind<Mock>) -> Result<(), BindError> {
    ///         bind.settings::<Settings>().map(drop)
    ///     }
    /// }
    /// ```
    ///
    /// # Errors
    ///
    /// [`BindError`] naming the component and the setting.
    fn check(bind: &Bind<E>) -> Result<(), BindError> {
        let _ = bind;
        Ok(())
    }
}

/// What a type-erased [`Interface::bind`] returns: the component's handle, boxed.
type Binding = Pin<Box<dyn Future<Output = Result<Box<dyn Any>, BindError>>>>;

/// A type-erased [`Interface::bind`].
type BindFn = fn(BindContext) -> Binding;

/// A type-erased [`Interface::check`].
type CheckFn = fn(BindContext) -> Result<(), BindError>;

/// A component's interface for one environment, type-erased.
#[derive(Clone, Copy)]
pub(crate) struct Binder {
    /// Binds it.
    pub(crate) bind: BindFn,
    /// Checks it without binding.
    pub(crate) check: CheckFn,
}

/// The environments a component runs in; filled in [`Component::interfaces`].
pub struct Interfaces<C> {
    entries: Vec<(&'static str, Binder)>,
    unavailable: Vec<(&'static str, &'static str)>,
    component: PhantomData<fn() -> C>,
}

/// What [`Interfaces`] holds once filled: the interfaces, and why some environments' are not in
/// this build.
pub(crate) struct Filled {
    pub(crate) entries: Vec<(&'static str, Binder)>,
    pub(crate) unavailable: Vec<(&'static str, &'static str)>,
}

impl<C: Component> Interfaces<C> {
    pub(crate) fn new() -> Self {
        Self {
            entries: Vec::new(),
            unavailable: Vec::new(),
            component: PhantomData,
        }
    }

    /// Adds the interface for environment `E`; the compiler checks that `C` implements it.
    pub fn add<E: Environment>(&mut self) -> &mut Self
    where
        C: Interface<E>,
    {
        self.entries.push((
            E::NAME,
            Binder {
                bind: bind_erased::<C, E>,
                check: check_erased::<C, E>,
            },
        ));
        self
    }

    /// Says what would add the interface for environment `E` that this build leaves out (a
    /// cargo feature): a run in `E` is then refused with it, not only with the environments
    /// the component has.
    ///
    /// ```
    /// use yarok_core::component::{Component, Declaration, Interfaces, Mock};
    ///
    /// struct Camera;
    ///
    /// impl Component for Camera {
    ///     fn declaration() -> Declaration {
    ///         Declaration::new("camera")
    ///     }
    ///
    ///     fn interfaces(interfaces: &mut Interfaces<Self>) {
    ///         #[cfg(not(feature = "camera"))]
    ///         interfaces.unavailable::<Mock>("the `camera` feature");
    ///     }
    /// }
    /// ```
    pub fn unavailable<E: Environment>(&mut self, what_adds_it: &'static str) -> &mut Self {
        self.unavailable.push((E::NAME, what_adds_it));
        self
    }

    pub(crate) fn filled(self) -> Filled {
        Filled {
            entries: self.entries,
            unavailable: self.unavailable,
        }
    }
}

impl<C> std::fmt::Debug for Interfaces<C> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.entries.iter().map(|(name, _)| name))
            .finish()
    }
}

fn check_erased<C: Interface<E>, E: Environment>(context: BindContext) -> Result<(), BindError> {
    C::check(&Bind::<E>::new(context)?)
}

fn bind_erased<C: Interface<E>, E: Environment>(context: BindContext) -> Binding {
    Box::pin(async move {
        let mut bind = Bind::<E>::new(context)?;
        let span = tracing::info_span!("component", path = %bind.path());
        let handle = tracing::Instrument::instrument(C::bind(&mut bind), span).await?;
        bind.warn_unread_settings();
        Ok(Box::new(handle) as Box<dyn Any>)
    })
}
