//! What an [`AnetA30`] shows any plugin: where its head is (`state`), where it is sent
//! (`command`), and the head's target a policy sets (its actuation, `…/x`, `…/y`, `…/z` in
//! millimetres).

use std::cell::Cell;
use std::rc::Rc;

use yarok_core::component::{Bind, Environment};

use super::{AnetA30, WORK_VOLUME_MM};

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
    // The head's target: where a policy last sent it, else where the head is.
    let target: Rc<Cell<Option<[f64; 3]>>> = Rc::default();
    let forgotten = Rc::clone(&target);
    bind.on_restart(move || forgotten.set(None));
    // In millimetres, as G-code moves it: named apart from the model's slide joints (metres).
    let prefix = bind.path().trim_start_matches('/').to_owned();
    let axes = std::array::from_fn::<_, 3, _>(|i| {
        (
            format!("{prefix}/{}_mm", ["x", "y", "z"][i]),
            [0.0, WORK_VOLUME_MM[i]],
        )
    });
    let (measured, read, shown, sent, driven) = (
        printer.clone(),
        Rc::clone(&target),
        printer.clone(),
        target,
        printer.clone(),
    );
    bind.actuation(
        axes,
        move || measured.at().to_vec(),
        move |_ahead| read.get().unwrap_or_else(|| shown.at()).to_vec(),
        move |targets| {
            let to = [targets[0], targets[1], targets[2]];
            if sent.replace(Some(to)) != Some(to) {
                driven.move_to(to);
            }
            Ok(())
        },
    );
}
