//! What an [`AnetA30`] shows any plugin: where its head is (`state`) and where it is sent
//! (`command`).

use yarok_core::component::{Bind, Environment};

use super::AnetA30;

/// Where the head is (millimetres).
#[derive(serde::Serialize)]
struct PrinterState {
    at: [f64; 3],
}

/// Where to send the head (millimetres).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct PrinterCommand {
    move_to: [f64; 3],
}

/// Publishes the printer's `state` and takes its `command`s.
pub(super) fn expose<E: Environment>(bind: &mut Bind<E>, printer: &AnetA30) {
    let shown = printer.clone();
    bind.state("state", move || PrinterState { at: shown.at() });
    let commanded = printer.clone();
    bind.command("command", move |PrinterCommand { move_to }| {
        commanded.move_to(move_to);
        Ok(())
    });
}
