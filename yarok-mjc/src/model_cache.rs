//! Compiled models shared by the worlds of a process and kept on disk between runs, in MuJoCo's
//! binary model format, keyed by what they were compiled from.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};

use sha2::{Digest, Sha256};
use yarok_core::compose::Composition;

use crate::error::ModelError;
use crate::model::Model;

/// What a cache file starts with, then a format number, the key it was compiled for, the
/// payload's length and its SHA-256.
const MAGIC: &[u8; 8] = b"YAROKMJB";
const FORMAT: u32 = 2;
const HEADER: usize = 8 + 4 + 32 + 8 + 32;

/// The most models a cache folder keeps; the least recently written go first.
const KEPT: usize = 256;

/// The models compiled in this process, by key, while a world uses them.
static SHARED: Mutex<Option<HashMap<[u8; 32], Weak<Model>>>> = Mutex::new(None);

/// Where a compiled model came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelSource {
    /// Another world of this process compiled it.
    Shared,
    /// Loaded from the cache folder.
    Disk,
    /// Compiled now (and written to the cache folder, if one is given).
    Compiled,
}

/// What identifies a composition's compiled model: MuJoCo's version, the composed MJCF, the
/// component keyframes and every asset file's name and bytes; `None` when an asset cannot be
/// read (compiling then reports it).
fn key(composition: &Composition) -> Option<[u8; 32]> {
    let mut hash = Sha256::new();
    hash.update(crate::mujoco_version().ok()?.as_bytes());
    hash.update(composition.to_xml().as_bytes());
    hash.update(format!("{:?}", composition.keyframes).as_bytes());
    for asset in &composition.assets {
        let bytes = std::fs::read(asset).ok()?;
        hash.update(asset.to_string_lossy().as_bytes());
        hash.update((bytes.len() as u64).to_le_bytes());
        hash.update(&bytes);
    }
    Some(hash.finalize().into())
}

impl Model {
    /// The compiled model of `composition`: the one another world of this process already
    /// uses, else the one in `folder` (MuJoCo's binary format; a corrupt, truncated or
    /// foreign file there, or one compiled for another world, is rebuilt, never loaded), else
    /// compiled now and written to
    /// `folder`. Worlds share a model safely: it is never changed after compiling.
    ///
    /// # Errors
    ///
    /// As [`Model::from_composition`]. A cache folder that cannot be written is only a
    /// warning.
    pub fn cached(
        composition: &Composition,
        folder: Option<&Path>,
    ) -> Result<(Arc<Model>, ModelSource), ModelError> {
        let Some(key) = key(composition) else {
            return Ok((
                Arc::new(Model::from_composition(composition)?),
                ModelSource::Compiled,
            ));
        };
        let mut shared = SHARED
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let shared = shared.get_or_insert_with(HashMap::new);
        shared.retain(|_, model| model.strong_count() > 0);
        if let Some(model) = shared.get(&key).and_then(Weak::upgrade) {
            return Ok((model, ModelSource::Shared));
        }
        let file = folder.map(|folder| folder.join(format!("{}.mjb", hex(&key))));
        let loaded = file.as_deref().and_then(|file| load(file, &key));
        let (model, source) = match loaded {
            Some(model) => (Arc::new(model), ModelSource::Disk),
            None => {
                let model = Arc::new(Model::from_composition(composition)?);
                if let Some(file) = &file {
                    save(&model, file, &key);
                }
                (model, ModelSource::Compiled)
            }
        };
        shared.insert(key, Arc::downgrade(&model));
        Ok((model, source))
    }

    /// The model in MuJoCo's binary format.
    pub fn to_binary(&self) -> Vec<u8> {
        let mj = self.mj();
        // SAFETY: the model is valid.
        let size = unsafe { mj.mj_sizeModel(self.raw()) };
        let mut buffer = vec![0u8; crate::model::to_usize(size)];
        // SAFETY: the buffer holds the size MuJoCo asked for; no file name is given.
        unsafe {
            mj.mj_saveModel(
                self.raw(),
                std::ptr::null(),
                buffer.as_mut_ptr().cast(),
                size,
            );
        }
        buffer
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Whether `file` is a regular file, or absent: anything else (a FIFO, a device, a folder) is
/// left alone — reading a FIFO would block start-up.
fn usable(file: &Path) -> bool {
    match std::fs::metadata(file) {
        Ok(metadata) if !metadata.is_file() => {
            tracing::warn!(file = %file.display(),
                "a compiled-model cache entry that is not a regular file; compiling without it");
            false
        }
        _ => true,
    }
}

/// The model in `file`, if the file is whole and was compiled for `key`; a file that is not is
/// removed.
fn load(file: &Path, key: &[u8; 32]) -> Option<Model> {
    if !usable(file) {
        return None;
    }
    let bytes = std::fs::read(file).ok()?;
    let entry = verified(&bytes);
    let model = match entry {
        Some((for_key, payload)) if for_key == key => Model::from_binary(payload).ok(),
        _ => None,
    };
    if model.is_none() {
        let another_format =
            bytes.starts_with(MAGIC) && bytes.get(8..12) != Some(&FORMAT.to_le_bytes()[..]);
        match entry {
            _ if another_format => tracing::debug!(file = %file.display(),
                "a compiled-model cache entry of another yarok version; rebuilding it"),
            Some(_) => tracing::warn!(file = %file.display(),
                "a compiled-model cache entry compiled for another world (copied or renamed \
                 from another entry); rebuilding it"),
            None => tracing::warn!(file = %file.display(),
                "a corrupt compiled-model cache entry; rebuilding it"),
        }
        let _ = std::fs::remove_file(file);
    }
    model
}

/// The key and payload of a cache file whose header and checksum hold.
fn verified(bytes: &[u8]) -> Option<(&[u8], &[u8])> {
    let (header, payload) = bytes.split_at_checked(HEADER)?;
    let (magic, rest) = header.split_at(MAGIC.len());
    let (format, rest) = rest.split_at(4);
    let (key, rest) = rest.split_at(32);
    let (length, checksum) = rest.split_at(8);
    let intact = magic == MAGIC
        && format == FORMAT.to_le_bytes()
        && length == (payload.len() as u64).to_le_bytes()
        && checksum == &Sha256::digest(payload)[..];
    intact.then_some((key, payload))
}

/// A cache file's bytes: the header [`verified`] checks, then `payload`.
fn entry(key: &[u8; 32], payload: &[u8]) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(HEADER + payload.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(key);
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&Sha256::digest(payload));
    bytes.extend_from_slice(payload);
    bytes
}

/// Writes `model`, compiled for `key`, to `file` whole or not at all (another process may be
/// reading it).
fn save(model: &Model, file: &Path, key: &[u8; 32]) {
    let bytes = entry(key, &model.to_binary());
    if !usable(file) {
        return;
    }
    let partial = PathBuf::from(format!("{}.{}.partial", file.display(), std::process::id()));
    let written = file
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| {
            yarok_core::output_file::write_in_own_folder(&partial, &bytes)?;
            std::fs::rename(&partial, file)
        });
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    if let Err(error) = written {
        tracing::warn!(file = %file.display(), %error, "cannot write the compiled-model cache");
    }
    if let Some(folder) = file.parent() {
        forget_oldest(folder);
    }
}

/// Removes the least recently written models beyond the [`KEPT`] newest, and partial writes
/// older than [`STALE_PARTIAL`] (of processes that died writing) — only files named as this
/// cache names them, so that other `.mjb` files in a shared folder are never touched.
fn forget_oldest(folder: &Path) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    let mut models: Vec<(std::time::SystemTime, PathBuf)> = Vec::new();
    for entry in entries.filter_map(Result::ok) {
        let (path, name) = (entry.path(), entry.file_name());
        let Some(name) = name.to_str() else {
            continue;
        };
        let Ok(modified) = entry.metadata().and_then(|m| m.modified()) else {
            continue;
        };
        if is_entry_name(name) {
            models.push((modified, path));
        } else if is_partial_name(name) && modified.elapsed().is_ok_and(|age| age > STALE_PARTIAL) {
            let _ = std::fs::remove_file(&path);
        }
    }
    if models.len() <= KEPT {
        return;
    }
    models.sort();
    for (_, old) in &models[..models.len() - KEPT] {
        let _ = std::fs::remove_file(old);
    }
}

/// How old a partial write must be to be taken for a dead process's.
const STALE_PARTIAL: std::time::Duration = std::time::Duration::from_secs(600);

/// Whether `name` is a cache entry's: 64 lowercase hex digits and `.mjb`.
fn is_entry_name(name: &str) -> bool {
    name.strip_suffix(".mjb").is_some_and(|key| {
        key.len() == 64
            && key
                .bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
    })
}

/// Whether `name` is a partial write's: an entry's name, a process id and `.partial`.
fn is_partial_name(name: &str) -> bool {
    name.strip_suffix(".partial")
        .and_then(|rest| rest.rsplit_once('.'))
        .is_some_and(|(entry, pid)| {
            is_entry_name(entry) && !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())
        })
}

#[cfg(test)]
mod tests {
    use super::{entry, is_entry_name, is_partial_name, verified};

    /// 100 000 damaged entries (bytes changed, cut short, lengthened, header numbers made
    /// extreme): none panics, and none is taken for this key's whole entry, so MuJoCo never
    /// reads damaged bytes (a changed key is another key's entry, which `load` refuses).
    #[test]
    fn no_damaged_entry_passes_for_whole() {
        let payload: Vec<u8> = (0..4096u32).map(|i| (i * 7919 % 251) as u8).collect();
        let valid = entry(&[7; 32], &payload);
        assert_eq!(verified(&valid), Some((&[7u8; 32][..], &payload[..])));
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut random = move |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n.max(1) as u64) as usize
        };
        for _ in 0..100_000 {
            let mut bytes = valid.clone();
            match random(4) {
                0 => {
                    for _ in 0..=random(4) {
                        let at = random(bytes.len());
                        bytes[at] ^= 1 << random(8);
                    }
                }
                1 => bytes.truncate(random(bytes.len())),
                2 => bytes.extend((0..=random(16)).map(|i| i as u8)),
                _ => {
                    let at = 8 + 4 + 32 + random(8);
                    bytes[at] = [0x00, 0xff, 0x7f, 0x80][random(4)];
                }
            }
            if let Some((key, loaded)) = verified(&bytes)
                && key == [7; 32]
            {
                assert!(bytes == valid, "a damaged entry passed for whole");
                assert!(loaded == payload);
            }
        }
    }

    #[test]
    fn only_the_caches_own_names_are_its_entries() {
        let key = "0123456789abcdef".repeat(4);
        assert!(is_entry_name(&format!("{key}.mjb")));
        assert!(is_partial_name(&format!("{key}.mjb.4242.partial")));
        for other in [
            "model.mjb",
            "robot.mjb",
            &format!("{}.mjb", key.to_uppercase()),
            &format!("{key}.mjb.x.partial"),
            &format!("{key}0.mjb"),
        ] {
            assert!(!is_entry_name(other) && !is_partial_name(other), "{other}");
        }
    }
}
