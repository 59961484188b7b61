//! Compiled models shared by the worlds of a process and kept on disk between runs, in MuJoCo's
//! binary model format, keyed by what they were compiled from.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};

use sha2::{Digest, Sha256};
use yarok_core::compose::Composition;

use crate::error::ModelError;
use crate::model::Model;

/// What a cache file starts with, then a format number, the payload's length and its SHA-256.
const MAGIC: &[u8; 8] = b"YAROKMJB";
const FORMAT: u32 = 1;
const HEADER: usize = 8 + 4 + 8 + 32;

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
    /// foreign file there is rebuilt, never loaded), else compiled now and written to
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
        let loaded = file.as_deref().and_then(load);
        let (model, source) = match loaded {
            Some(model) => (Arc::new(model), ModelSource::Disk),
            None => {
                let model = Arc::new(Model::from_composition(composition)?);
                if let Some(file) = &file {
                    save(&model, file);
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

/// The model in `file`, if the file is whole and ours; a file that is not is removed.
fn load(file: &Path) -> Option<Model> {
    let bytes = std::fs::read(file).ok()?;
    let payload = verified(&bytes);
    let model = payload.and_then(|payload| Model::from_binary(payload).ok());
    if model.is_none() {
        tracing::warn!(file = %file.display(), "a corrupt compiled-model cache entry; rebuilding it");
        let _ = std::fs::remove_file(file);
    }
    model
}

/// The payload of a cache file whose header and checksum hold.
fn verified(bytes: &[u8]) -> Option<&[u8]> {
    let (header, payload) = bytes.split_at_checked(HEADER)?;
    let length = u64::from_le_bytes(header[12..20].try_into().ok()?);
    let intact = &header[..8] == MAGIC
        && header[8..12] == FORMAT.to_le_bytes()
        && length == payload.len() as u64
        && header[20..] == Sha256::digest(payload)[..];
    intact.then_some(payload)
}

/// Writes `model` to `file` whole or not at all (another process may be reading it).
fn save(model: &Model, file: &Path) {
    let payload = model.to_binary();
    let mut bytes = Vec::with_capacity(HEADER + payload.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&Sha256::digest(&payload));
    bytes.extend_from_slice(&payload);
    let written = file
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| {
            let partial =
                PathBuf::from(format!("{}.{}.partial", file.display(), std::process::id()));
            std::fs::write(&partial, &bytes)?;
            std::fs::rename(&partial, file)
        });
    if let Err(error) = written {
        tracing::warn!(file = %file.display(), %error, "cannot write the compiled-model cache");
    }
    if let Some(folder) = file.parent() {
        forget_oldest(folder);
    }
}

/// Removes the least recently written models beyond the [`KEPT`] newest.
fn forget_oldest(folder: &Path) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    let mut models: Vec<(std::time::SystemTime, PathBuf)> = entries
        .filter_map(Result::ok)
        .filter(|entry| entry.path().extension().is_some_and(|e| e == "mjb"))
        .filter_map(|entry| Some((entry.metadata().ok()?.modified().ok()?, entry.path())))
        .collect();
    if models.len() <= KEPT {
        return;
    }
    models.sort();
    for (_, old) in &models[..models.len() - KEPT] {
        let _ = std::fs::remove_file(old);
    }
}
