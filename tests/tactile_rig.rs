//! The tactile rig: a press is as deep as asked, deeper presses feel more, impossible presses
//! are refused, and rigs on two threads collect the same samples, byte for byte, as one rig.

use yarok::components::worlds::{Press, PressError, Sample, TactileRigWorld};
use yarok_test::assert_says;

/// The samples of `presses` collected by one rig set up as `settings` say.
fn collect(settings: &[&str], presses: Vec<Press>) -> Vec<Sample> {
    let samples = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let out = std::rc::Rc::clone(&samples);
    let mut builder = yarok::platform().world::<TactileRigWorld>();
    for setting in settings {
        builder = builder.set(setting).unwrap();
    }
    builder
        .behaviour(move |pl| async move {
            let rig: TactileRigWorld = pl.get("/")?;
            for press in presses {
                let sample = rig.press(press).await?;
                out.borrow_mut().push(sample);
            }
            Ok(())
        })
        .run()
        .unwrap();
    samples.take()
}

fn grid() -> Vec<Press> {
    let mut presses = Vec::new();
    for depth in [0.0005, 0.001, 0.0015] {
        for x in [-0.003, 0.0, 0.003] {
            presses.push(Press {
                at: [x, if x == 0.0 { 0.0 } else { 0.002 }],
                depth,
            });
        }
    }
    presses
}

#[test]
fn a_press_is_as_deep_as_asked_and_deeper_presses_feel_more() {
    for sensor in ["geltip", "digit"] {
        let setting = format!("sensor=\"{sensor}\"");
        let samples = collect(&[&setting, "parallel=false"], grid());
        for sample in &samples {
            // The camera measures indentation along its rays, which meet the GelTip's dome
            // aslant off its axis: there a press feels deeper than its depth along the axis.
            let felt = sample.contact.max_indentation;
            let on_axis = sensor == "digit" || sample.press.at[0] == 0.0;
            assert!(
                sample.contact.in_contact && (felt - sample.press.depth).abs() < 1e-4
                    || !on_axis && felt > sample.press.depth,
                "{sensor}: {:?} felt {felt} m deep",
                sample.press
            );
        }
        for shallow in 0..3 {
            let areas: Vec<f64> = (0..3)
                .map(|d| samples[3 * d + shallow].contact.area)
                .collect();
            assert!(
                areas[0] < areas[1] && areas[1] < areas[2],
                "{sensor}: {areas:?}"
            );
        }
        let untouched = collect(
            &[&setting, "parallel=false"],
            vec![Press {
                at: [0.0, 0.0],
                depth: 0.0,
            }],
        );
        assert!(
            !untouched[0].contact.in_contact,
            "{sensor}: {:?}",
            untouched[0].contact
        );
    }
}

#[test]
fn two_rigs_on_two_threads_collect_the_same_samples_as_one() {
    let presses = grid();
    let one = collect(&["sensor=\"digit\""], presses.clone());
    let (even, odd): (Vec<_>, Vec<_>) = presses
        .iter()
        .enumerate()
        .partition(|(index, _)| index % 2 == 0);
    let take = |half: Vec<(usize, &Press)>| half.into_iter().map(|(_, p)| *p).collect::<Vec<_>>();
    let (even, odd) = (take(even), take(odd));
    let (from_even, from_odd) = std::thread::scope(|scope| {
        let even = scope.spawn(|| collect(&["sensor=\"digit\"", "parallel=false"], even));
        let odd = scope.spawn(|| collect(&["sensor=\"digit\"", "parallel=false"], odd));
        (even.join().unwrap(), odd.join().unwrap())
    });
    assert_eq!(one.len(), from_even.len() + from_odd.len());
    for (index, sample) in one.iter().enumerate() {
        let other = if index % 2 == 0 {
            &from_even[index / 2]
        } else {
            &from_odd[index / 2]
        };
        assert_eq!(sample.press, other.press);
        assert_eq!(sample.head, other.head, "sample {index}");
        assert!(
            sample.image == other.image,
            "sample {index}: the images differ"
        );
        assert!(
            sample.depth == other.depth,
            "sample {index}: the depths differ"
        );
    }
}

#[test]
fn impossible_presses_are_refused() {
    yarok::platform()
        .world::<TactileRigWorld>()
        .behaviour(|pl| async move {
            let rig: TactileRigWorld = pl.get("/")?;
            for (at, depth) in [
                ([0.02, 0.0], 0.001),
                ([0.0, 0.0], f64::NAN),
                ([0.0, 0.0], -0.001),
            ] {
                match rig.press(Press { at, depth }).await {
                    Err(PressError::Impossible { .. }) => {}
                    other => panic!("{at:?} {depth}: {other:?}"),
                }
            }
            Ok(())
        })
        .run()
        .unwrap();
    let error = yarok::platform()
        .world::<TactileRigWorld>()
        .set("sensor=\"gelsite\"")
        .unwrap()
        .behaviour(|_| async { Ok(()) })
        .run()
        .unwrap_err()
        .to_string();
    assert_says(&error, &["sensor must be", "gelsite"]);
}
