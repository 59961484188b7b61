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
}

/// What a type-erased [`Interface::bind`] returns: the component's handle, boxed.
type Binding = Pin<Box<dyn Future<Output = Result<Box<dyn Any>, BindError>>>>;

/// A type-erased [`Interface::bind`].
pub(crate) type BindFn = fn(BindContext) -> Binding;

/// The environments a component runs in; filled in [`Component::interfaces`].
pub struct Interfaces<C> {
    entries: Vec<(&'static str, BindFn)>,
    unavailable: Vec<(&'static str, &'static str)>,
    component: PhantomData<fn() -> C>,
}

/// What [`Interfaces`] holds once filled: the interfaces, and why some environments' are not in
/// this build.
pub(crate) struct Filled {
    pub(crate) entries: Vec<(&'static str, BindFn)>,
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
        self.entries.push((E::NAME, bind_erased::<C, E>));
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

fn bind_erased<C: Interface<E>, E: Environment>(context: BindContext) -> Binding {
    Box::pin(async move {
        let mut bind = Bind::<E>::new(context)?;
        let span = tracing::info_span!("component", path = %bind.path());
        let handle = tracing::Instrument::instrument(C::bind(&mut bind), span).await?;
        bind.warn_unread_settings();
        Ok(Box::new(handle) as Box<dyn Any>)
    })
}
