//! Compiled models shared in a process and kept on disk: a cache hit loads a model identical to
//! a fresh compile (byte for byte in MuJoCo's binary format); a corrupt, truncated or foreign
//! entry, or another world's, is rebuilt, never loaded; worlds alive at once share one model; a FIFO where an entry
//! should be does not block start-up; eviction touches only the cache's own files.

use std::sync::Arc;

use yarok_core::component::{Component, Declaration};
use yarok_core::compose::{Composition, compose};
use yarok_mjc::{Model, ModelSource};

/// A model of its own per test: other tests of this process must not share it.
macro_rules! world {
    ($name:ident, $size:literal) => {
        struct $name;
        impl Component for $name {
            fn declaration() -> Declaration {
                Declaration::new(stringify!($name)).template(concat!(
                    r#"<mujoco><worldbody><geom type="plane" size="1 1 0.1"/>
                         <body pos="0 0 1"><freejoint/><geom size=""#,
                    $size,
                    r#""/></body></worldbody></mujoco>"#
                ))
            }
        }
    };
}

world!(CachedWorld, "0.11");
world!(CorruptedWorld, "0.12");
world!(SharedWorld, "0.13");

/// A way to damage a cache file's bytes.
type Damage = fn(&mut Vec<u8>);

fn cached(composition: &Composition, folder: &std::path::Path) -> (Arc<Model>, ModelSource) {
    Model::cached(composition, Some(folder)).unwrap()
}

/// The one cache file in `folder`.
fn entry(folder: &std::path::Path) -> std::path::PathBuf {
    let files: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    files[0].clone()
}

#[test]
fn a_cache_hit_is_the_model_a_fresh_compile_gives() {
    let folder = tempfile::tempdir().unwrap();
    let composition = compose::<CachedWorld>().unwrap();
    let (compiled, source) = cached(&composition, folder.path());
    assert_eq!(source, ModelSource::Compiled);
    let fresh = compiled.to_binary();
    drop(compiled);
    let (loaded, source) = cached(&composition, folder.path());
    assert_eq!(source, ModelSource::Disk);
    assert!(loaded.to_binary() == fresh, "the loaded model differs");
    assert!(Model::from_composition(&composition).unwrap().to_binary() == fresh);
}

#[test]
fn a_damaged_entry_is_rebuilt_never_loaded() {
    let folder = tempfile::tempdir().unwrap();
    let composition = compose::<CorruptedWorld>().unwrap();
    drop(cached(&composition, folder.path()));
    let file = entry(folder.path());
    let good = std::fs::read(&file).unwrap();
    let flip_in_payload = |bytes: &mut Vec<u8>| {
        let middle = bytes.len() / 2;
        bytes[middle] ^= 0x40;
    };
    let damages: [(&str, Damage); 4] = [
        ("a flipped bit in the model", flip_in_payload),
        ("a truncated file", |b| b.truncate(b.len() - 100)),
        ("another format", |b| b[0] = b'X'),
        ("an empty file", Vec::clear),
    ];
    for (damage, apply) in damages {
        let mut bytes = good.clone();
        apply(&mut bytes);
        std::fs::write(&file, &bytes).unwrap();
        let (model, source) = cached(&composition, folder.path());
        assert_eq!(source, ModelSource::Compiled, "{damage}: rebuilt");
        assert!(model.to_binary() == good[good.len() - model.to_binary().len()..]);
        drop(model);
        assert_eq!(
            std::fs::read(&file).unwrap(),
            good,
            "{damage}: the entry is whole again"
        );
        let (_, source) = cached(&composition, folder.path());
        assert_eq!(source, ModelSource::Disk, "{damage}: loaded once rebuilt");
    }
}

#[test]
fn worlds_alive_at_once_share_one_model() {
    let composition = compose::<SharedWorld>().unwrap();
    let (first, source) = Model::cached(&composition, None).unwrap();
    assert_eq!(source, ModelSource::Compiled);
    let (second, source) = Model::cached(&composition, None).unwrap();
    assert_eq!(source, ModelSource::Shared);
    assert!(Arc::ptr_eq(&first, &second));
    drop((first, second));
    let (_, source) = Model::cached(&composition, None).unwrap();
    assert_eq!(
        source,
        ModelSource::Compiled,
        "compiled again once no world used it"
    );
}

world!(FifoWorld, "0.14");
world!(ThisWorld, "0.16");
world!(OtherWorld, "0.17");

/// Another world's entry copied under this world's key (whole, its checksum right) is not
/// loaded: the world would fail to bind on every run, naming no cache. It is rebuilt.
#[test]
fn another_worlds_entry_under_this_key_is_rebuilt() {
    let folder = tempfile::tempdir().unwrap();
    let this = compose::<ThisWorld>().unwrap();
    let other_folder = tempfile::tempdir().unwrap();
    let other = compose::<OtherWorld>().unwrap();
    let (this_model, _) = cached(&this, folder.path());
    let (other_model, _) = cached(&other, other_folder.path());
    let fresh = this_model.to_binary();
    assert!(other_model.to_binary() != fresh);
    drop((this_model, other_model));
    std::fs::copy(entry(other_folder.path()), entry(folder.path())).unwrap();
    let (model, source) = cached(&this, folder.path());
    assert_eq!(source, ModelSource::Compiled);
    assert!(model.to_binary() == fresh, "this world's model, compiled");
    drop(model);
    let (model, source) = cached(&this, folder.path());
    assert_eq!(source, ModelSource::Disk, "loaded once rebuilt");
    assert!(model.to_binary() == fresh);
}
world!(SharedFolderWorld, "0.15");

/// A FIFO (or any file that is not a regular one) where an entry should be: start-up does not
/// block reading it; the model is compiled, and the FIFO left alone.
#[test]
fn a_fifo_in_place_of_an_entry_is_skipped_and_the_model_compiled() {
    let folder = tempfile::tempdir().unwrap();
    let composition = compose::<FifoWorld>().unwrap();
    let (model, _) = cached(&composition, folder.path());
    drop(model);
    let file = entry(folder.path());
    std::fs::remove_file(&file).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(&file)
        .status()
        .unwrap();
    assert!(made.success());
    let path = folder.path().to_owned();
    let (sender, receiver) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let composition = compose::<FifoWorld>().unwrap();
        let _ = sender.send(cached(&composition, &path).1);
    });
    let source = receiver
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("start-up blocked on the FIFO");
    assert_eq!(source, ModelSource::Compiled);
    use std::os::unix::fs::FileTypeExt;
    assert!(
        std::fs::symlink_metadata(&file)
            .unwrap()
            .file_type()
            .is_fifo()
    );
}

/// A cache folder shared with other `.mjb` files: eviction removes only the cache's own oldest
/// entries, and partial writes a dead process left behind (older than ten minutes).
#[test]
fn eviction_touches_only_the_caches_own_files() {
    let folder = tempfile::tempdir().unwrap();
    let old = |path: &std::path::Path| {
        let touched = std::process::Command::new("touch")
            .args(["-d", "2 hours ago"])
            .arg(path)
            .status()
            .unwrap();
        assert!(touched.success());
    };
    let theirs = ["robot.mjb", "scene.mjb", "notes.txt"].map(|name| folder.path().join(name));
    for path in &theirs {
        std::fs::write(path, b"someone else's").unwrap();
        old(path);
    }
    for i in 0..300 {
        let path = folder.path().join(format!("{i:064x}.mjb"));
        std::fs::write(&path, b"an old entry").unwrap();
        old(&path);
    }
    let stale = folder.path().join(format!("{:064x}.mjb.99999.partial", 7));
    let fresh = folder.path().join(format!("{:064x}.mjb.99998.partial", 8));
    std::fs::write(&stale, b"half").unwrap();
    old(&stale);
    std::fs::write(&fresh, b"being written").unwrap();
    let composition = compose::<SharedFolderWorld>().unwrap();
    let (_model, source) = cached(&composition, folder.path());
    assert_eq!(source, ModelSource::Compiled);
    let names: Vec<String> = std::fs::read_dir(folder.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    let entries = names
        .iter()
        .filter(|n| n.len() == 68 && n.ends_with(".mjb"))
        .count();
    assert_eq!(entries, 256, "{} entries", entries);
    for path in &theirs {
        assert!(path.exists(), "{} was removed", path.display());
    }
    assert!(!stale.exists() && fresh.exists());
}
