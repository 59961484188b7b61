//! Episodes in `sim`: the arm, the gripper and the blocks back where the world started, a motion
//! under way when one begins ended as stopped, platform time going on.

use yarok::components::grippers::Robotiq2f85;
use yarok::components::robots::ur::{MotionError, Ur5e};
use yarok::components::toys::Block;
use yarok::components::worlds::PickAndPlaceWorld;

#[test]
fn an_episode_puts_the_arm_the_gripper_and_the_blocks_back_where_they_started() {
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .behaviour(|pl| async move {
            let arm: Ur5e = pl.get("/arm")?;
            let gripper: Robotiq2f85 = pl.get("/arm/gripper")?;
            let block: Block = pl.get("/large")?;
            pl.tick().await?;
            let (start_q, start_block, start_fingers) =
                (arm.q(), block.position(), gripper.position());

            let mut away = start_q;
            away[0] += 0.4;
            away[1] -= 0.2;
            arm.move_j(away).await?;
            gripper.close().await?;
            assert!(arm.q()[0] > start_q[0] + 0.39, "the arm moved");
            assert!(
                gripper.position() > start_fingers + 100,
                "the gripper closed"
            );

            // A motion under way when the episode begins ends as stopped.
            let mut back = away;
            back[0] -= 0.3;
            let before = pl.time();
            let (motion, episode) = tokio::join!(arm.move_j(back), async {
                pl.wait_seconds(0.1).await?;
                Ok::<_, yarok::core::BoxError>(pl.begin_episode(3)?)
            });
            let episode = episode?;
            assert!(matches!(motion, Err(MotionError::Stopped)), "{motion:?}");
            assert_eq!(episode.number, 3);
            assert!(pl.time() > before, "platform time goes on");
            assert_eq!(arm.q(), start_q, "the arm is where it started");
            assert_eq!(block.position(), start_block, "so is the block");
            assert_eq!(gripper.position(), start_fingers, "and the fingers");

            pl.wait_seconds(0.5).await?;
            for (q, start) in arm.q().iter().zip(start_q) {
                assert!(
                    (q - start).abs() < 1e-3,
                    "the arm holds its start: {q} vs {start}"
                );
            }
            assert!(
                gripper.position() <= start_fingers + 1,
                "the gripper stays open"
            );
            Ok(())
        })
        .run()
        .unwrap();
}

/// An episode number begun twice in a run is an error (its recordings would be overwritten),
/// and the first episode's MCAP file is left as it was recorded.
#[test]
fn an_episode_number_begun_twice_is_an_error_and_its_recording_is_kept() {
    use yarok::core::runtime::EpisodeError;
    let folder = tempfile::tempdir().unwrap();
    let mcap = folder.path().join("run.mcap");
    let episode_file = folder.path().join("run_episode_0003.mcap");
    let watched = episode_file.clone();
    let kept = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let first = std::rc::Rc::clone(&kept);
    yarok::platform()
        .world::<PickAndPlaceWorld>()
        .set(&format!(
            "plugins/mcap/path={:?}",
            mcap.display().to_string()
        ))
        .unwrap()
        .behaviour(move |pl| async move {
            pl.begin_episode(3)?;
            pl.wait_seconds(0.2).await?;
            pl.begin_episode(4)?;
            pl.tick().await?;
            // Episode 3's file, finished as episode 4 began.
            *first.borrow_mut() = std::fs::read(&watched)?;
            let error = pl.begin_episode(3).unwrap_err();
            assert!(
                matches!(error, EpisodeError::Repeated { number: 3 }),
                "{error}"
            );
            assert!(error.to_string().contains("already begun"), "{error}");
            pl.wait_seconds(0.1).await?;
            Ok(())
        })
        .run()
        .unwrap();
    let first = kept.borrow();
    assert!(
        first.len() > 1000,
        "episode 3's file held {} bytes",
        first.len()
    );
    assert!(
        std::fs::read(&episode_file).unwrap() == *first,
        "episode 3's file changed"
    );
}
