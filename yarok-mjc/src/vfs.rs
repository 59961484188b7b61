//! MuJoCo's virtual file system, used to compile MJCF held in memory.

use std::ffi::CString;

use crate::error::ModelError;
use crate::sys;

/// An owned `mjVFS`; boxed because MuJoCo keeps pointers into it.
pub(crate) struct Vfs {
    raw: Box<sys::mjVFS>,
    mj: &'static sys::MuJoCo,
}

impl Vfs {
    pub(crate) fn new(mj: &'static sys::MuJoCo) -> Self {
        let mut raw = Box::<sys::mjVFS>::default();
        // SAFETY: `raw` is a writable mjVFS that mj_deleteVFS frees on drop.
        unsafe { mj.mj_defaultVFS(&mut *raw) };
        Self { raw, mj }
    }

    pub(crate) fn add(&mut self, name: &str, bytes: &[u8]) -> Result<(), ModelError> {
        let c_name = CString::new(name).map_err(|_| ModelError::InteriorNul {
            what: format!("asset name {name:?}"),
        })?;
        let len = i32::try_from(bytes.len()).map_err(|_| ModelError::Asset {
            name: name.to_owned(),
            reason: "larger than 2 GiB",
        })?;
        // SAFETY: the VFS is initialised, `c_name` is NUL-terminated and `bytes` holds `len`
        // bytes, which MuJoCo copies.
        let status = unsafe {
            self.mj
                .mj_addBufferVFS(&mut *self.raw, c_name.as_ptr(), bytes.as_ptr().cast(), len)
        };
        match status {
            0 => Ok(()),
            2 => Err(ModelError::Asset {
                name: name.to_owned(),
                reason: "repeated name",
            }),
            _ => Err(ModelError::Asset {
                name: name.to_owned(),
                reason: "MuJoCo refused it",
            }),
        }
    }

    pub(crate) fn as_ptr(&self) -> *const sys::mjVFS {
        &*self.raw
    }
}

impl Drop for Vfs {
    fn drop(&mut self) {
        // SAFETY: the VFS was initialised by mj_defaultVFS and is freed once.
        unsafe { self.mj.mj_deleteVFS(&mut *self.raw) }
    }
}
