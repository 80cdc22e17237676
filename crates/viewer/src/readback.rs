//! Reading a small GPU buffer back a few frames late, never waiting: copy into the staging
//! buffer, submit, ask for the mapping, and take the contents on a later frame once it
//! completed (a failed mapping is retried with a later copy). One read in flight at a time.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

const PENDING: u8 = 0;
const MAPPED: u8 = 1;
const FAILED: u8 = 2;

/// A staging buffer and the state of its mapping.
pub(crate) struct Readback {
    staging: wgpu::Buffer,
    state: Option<Arc<AtomicU8>>,
}

impl Readback {
    /// A staging buffer of `size` bytes.
    pub fn new(device: &wgpu::Device, label: &str, size: u64) -> Readback {
        Readback {
            staging: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            state: None,
        }
    }

    /// Whether no read is in flight (a copy into [`Readback::staging`] may be recorded).
    pub fn idle(&self) -> bool {
        self.state.is_none()
    }

    /// The buffer to copy into.
    pub fn staging(&self) -> &wgpu::Buffer {
        &self.staging
    }

    /// After the copy was submitted: asks for the mapping.
    pub fn request(&mut self) {
        let state = Arc::new(AtomicU8::new(PENDING));
        let done = state.clone();
        self.staging
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |r| {
                done.store(if r.is_ok() { MAPPED } else { FAILED }, Ordering::Release);
            });
        self.state = Some(state);
    }

    /// The contents, once the mapping completed; `None` while it is pending or after it
    /// failed (the reader is then idle again).
    pub fn take<T: bytemuck::Pod>(&mut self) -> Option<Vec<T>> {
        match self.state.as_ref()?.load(Ordering::Acquire) {
            PENDING => return None,
            MAPPED => self.state = None,
            _ => {
                self.state = None;
                return None;
            }
        }
        let out = self
            .staging
            .slice(..)
            .get_mapped_range()
            .ok()
            .map(|data| bytemuck::pod_collect_to_vec::<u8, T>(&data));
        self.staging.unmap();
        out
    }
}
