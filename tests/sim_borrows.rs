//! A borrow of the simulation data held across an `.await` stops the run with an error that
//! names the cause, instead of a `BorrowMutError` panic inside yarok.

use std::cell::RefCell;
use std::rc::Rc;

use yarok::mjc::{Data, SimBind};
use yarok::{Bind, Component, Declaration, RuntimeError};

#[derive(Clone)]
struct Pendulum {
    data: Rc<RefCell<Data>>,
}

impl Component for Pendulum {
    fn declaration() -> Declaration {
        Declaration::new("pendulum").template(
            r#"<mujoco><worldbody><body name="bob"><joint name="hinge"/><geom size="0.1"/></body></worldbody></mujoco>"#,
        )
    }

    fn bind(bind: &mut Bind<'_>) -> Result<Self, RuntimeError> {
        Ok(Pendulum {
            data: bind.sim()?.data(),
        })
    }
}

#[test]
#[expect(
    clippy::await_holding_refcell_ref,
    reason = "the mistake this test makes on purpose"
)]
fn a_borrow_held_across_an_await_is_an_error_naming_the_cause() {
    let error = yarok::platform()
        .world::<Pendulum>()
        .behaviour(|pl| async move {
            let pendulum: Pendulum = pl.get("/")?;
            let data = pendulum.data.borrow();
            pl.tick().await?;
            drop(data);
            Ok(())
        })
        .run()
        .unwrap_err();
    let message = error.to_string();
    assert!(
        matches!(error, RuntimeError::Backend(_)) && message.contains("across an `.await`"),
        "{message}"
    );
}
