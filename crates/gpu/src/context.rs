//! Device setup, separate from the work (as in the wgpu examples) so that tests, headless
//! runs, the viewer and benchmarks share one path.
//!
//! A hardware adapter is preferred (discrete, then integrated, then virtual); the software
//! adapter (lavapipe on Vulkan, llvmpipe on GL) is taken when nothing else exists. The
//! backend can be pinned with `--gpu-backend` or the `WGPU_BACKEND` environment variable,
//! an adapter picked by name with `WGPU_ADAPTER_NAME`. The device gets the adapter's own
//! limits, not the WebGPU defaults.

use std::fmt;
use std::str::FromStr;
use std::sync::{Arc, Mutex};

use super::GpuError;
use super::pipelines::Pipelines;
use super::selftest;
use super::tessellator::Tessellator;

/// Which graphics API to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BackendChoice {
    /// Every backend compiled in, or `WGPU_BACKEND` when set.
    #[default]
    Auto,
    /// Vulkan (lavapipe is the software one).
    Vulkan,
    /// OpenGL / GLES (llvmpipe is the software one).
    Gl,
    /// Metal.
    Metal,
    /// Direct3D 12.
    Dx12,
}

/// A backend name that is not one of `auto, vulkan, gl, metal, dx12`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown GPU backend {0:?} (expected auto, vulkan, gl, metal or dx12)")]
pub struct UnknownBackend(pub String);

impl FromStr for BackendChoice {
    type Err = UnknownBackend;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "auto" => Ok(BackendChoice::Auto),
            "vulkan" | "vk" => Ok(BackendChoice::Vulkan),
            "gl" | "gles" | "opengl" => Ok(BackendChoice::Gl),
            "metal" => Ok(BackendChoice::Metal),
            "dx12" | "d3d12" => Ok(BackendChoice::Dx12),
            other => Err(UnknownBackend(other.to_owned())),
        }
    }
}

impl fmt::Display for BackendChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BackendChoice::Auto => "auto",
            BackendChoice::Vulkan => "vulkan",
            BackendChoice::Gl => "gl",
            BackendChoice::Metal => "metal",
            BackendChoice::Dx12 => "dx12",
        })
    }
}

impl BackendChoice {
    /// The wgpu backends this choice allows.
    #[must_use]
    pub fn backends(self) -> wgpu::Backends {
        match self {
            BackendChoice::Auto => wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all()),
            BackendChoice::Vulkan => wgpu::Backends::VULKAN,
            BackendChoice::Gl => wgpu::Backends::GL,
            BackendChoice::Metal => wgpu::Backends::METAL,
            BackendChoice::Dx12 => wgpu::Backends::DX12,
        }
    }
}

/// How to choose the device.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ContextOptions {
    /// The backend.
    pub backend: BackendChoice,
    /// Only adapters whose name contains this (case-insensitive); defaults to
    /// `WGPU_ADAPTER_NAME`.
    pub adapter_name: Option<String>,
}

impl ContextOptions {
    /// Options with the given backend and the adapter name from `WGPU_ADAPTER_NAME`.
    #[must_use]
    pub fn from_env(backend: BackendChoice) -> ContextOptions {
        ContextOptions {
            backend,
            adapter_name: std::env::var("WGPU_ADAPTER_NAME")
                .ok()
                .filter(|s| !s.is_empty()),
        }
    }
}

/// An adapter, its device and queue: what work is handed. The pipelines are a separate
/// value ([`Pipelines`]), returned beside the context when it opens.
#[derive(Debug)]
pub struct GpuContext {
    /// The instance the adapter came from.
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The device, with the adapter's own limits.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The first uncaptured error or loss the device reported (see
    /// [`GpuContext::check_health`]).
    health: Arc<Mutex<Option<String>>>,
}

/// The hint printed when no adapter exists.
pub const INSTALL_HINT: &str = "install a Vulkan driver: on Debian/Ubuntu the software one is \
`sudo apt-get install mesa-vulkan-drivers libvulkan1` (lavapipe), and Mesa's OpenGL one is \
`sudo apt-get install libegl1 libgl1-mesa-dri` (llvmpipe); with a GPU, its vendor's driver. Then pin it if needed: WGPU_BACKEND=vulkan \
VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

fn type_rank(t: wgpu::DeviceType) -> u8 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 3,
        wgpu::DeviceType::Other => 4,
    }
}

fn backend_rank(b: wgpu::Backend) -> u8 {
    match b {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 0,
        wgpu::Backend::Gl => 1,
        _ => 2,
    }
}

/// The real graphics APIs in `backends`, by the names `--gpu-backend` takes
/// (`vulkan, gl`).
#[must_use]
pub fn backend_names(backends: wgpu::Backends) -> String {
    let names: Vec<&str> = [
        (wgpu::Backends::VULKAN, "vulkan"),
        (wgpu::Backends::GL, "gl"),
        (wgpu::Backends::METAL, "metal"),
        (wgpu::Backends::DX12, "dx12"),
    ]
    .iter()
    .filter(|(b, _)| backends.contains(*b))
    .map(|(_, n)| *n)
    .collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

/// Records the device's first uncaptured error or loss instead of panicking.
fn watch(device: &wgpu::Device) -> Arc<Mutex<Option<String>>> {
    let health = Arc::new(Mutex::new(None::<String>));
    let record = |slot: &Arc<Mutex<Option<String>>>, message: String| {
        let mut h = slot
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        h.get_or_insert(message);
    };
    let on_error = Arc::clone(&health);
    device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
        record(&on_error, e.to_string());
    }));
    let on_lost = Arc::clone(&health);
    device.set_device_lost_callback(move |reason, message| {
        record(
            &on_lost,
            if message.is_empty() {
                format!("device lost ({reason:?})")
            } else {
                format!("device lost ({reason:?}): {message}")
            },
        );
    });
    health
}

/// The order adapters are preferred in (smaller first): hardware before virtual before
/// software; Vulkan, Metal and DX12 before GL.
fn preference(info: &wgpu::AdapterInfo) -> (u8, u8) {
    (type_rank(info.device_type), backend_rank(info.backend))
}

/// One adapter as `splinescope adapters` reports it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AdapterReport {
    /// Its name.
    pub name: String,
    /// `Vulkan`, `Gl`, …
    pub backend: String,
    /// `DiscreteGpu`, `IntegratedGpu`, `VirtualGpu`, `Cpu` or `Other`.
    pub device_type: String,
    /// The driver's name and version information.
    pub driver: String,
    /// `max_storage_buffer_binding_size` in bytes: how many samples one chunk can hold.
    pub max_storage_binding_bytes: u64,
    /// `max_buffer_size` in bytes.
    pub max_buffer_bytes: u64,
    /// `max_compute_workgroups_per_dimension`: past it dispatches go 2D.
    pub max_workgroups_per_dimension: u32,
    /// Whether GPU timestamp queries are available (per-stage timings).
    pub timestamps: bool,
    /// `passed`, or why the device could not be used (the kernel self-test's finding,
    /// or the device request's error).
    pub self_test: String,
    /// Whether offscreen commands (`render`, `eval --backend gpu`, `bench`, the headless
    /// gallery) would pick this adapter with these options.
    pub chosen: bool,
}

/// Every adapter the options allow, in order of preference, each opened and self-tested;
/// the first that passes is marked `chosen` (the one [`GpuContext::new`] returns).
#[must_use]
pub fn survey(opts: &ContextOptions) -> Vec<AdapterReport> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: opts.backend.backends(),
        ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
    });
    let mut all = pollster::block_on(instance.enumerate_adapters(opts.backend.backends()));
    all.sort_by_key(|a| preference(&a.get_info()));
    let wanted = opts.adapter_name.as_ref().map(|n| n.to_lowercase());
    let mut chosen_yet = false;
    all.iter()
        .map(|adapter| {
            let info = adapter.get_info();
            let limits = adapter.limits();
            let matches = wanted
                .as_ref()
                .is_none_or(|w| info.name.to_lowercase().contains(w));
            let self_test = match open_and_test(adapter) {
                Ok(_) => "passed".to_owned(),
                Err(why) => format!("failed: {why}"),
            };
            let chosen = matches && !chosen_yet && self_test == "passed";
            chosen_yet |= chosen;
            AdapterReport {
                name: info.name.clone(),
                backend: format!("{:?}", info.backend),
                device_type: format!("{:?}", info.device_type),
                driver: [info.driver.as_str(), info.driver_info.as_str()]
                    .iter()
                    .filter(|s| !s.is_empty())
                    .copied()
                    .collect::<Vec<_>>()
                    .join(" "),
                max_storage_binding_bytes: limits.max_storage_buffer_binding_size,
                max_buffer_bytes: limits.max_buffer_size,
                max_workgroups_per_dimension: limits.max_compute_workgroups_per_dimension,
                timestamps: adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY),
                self_test,
                chosen,
            }
        })
        .collect()
}

/// Opens `adapter`'s device and runs the kernel self-test on it: the device, its queue
/// and the tested tessellation pipelines, or why the adapter is refused.
fn open_and_test(
    adapter: &wgpu::Adapter,
) -> Result<(wgpu::Device, wgpu::Queue, Tessellator), Refusal> {
    let (device, queue) = open_device(adapter).map_err(Refusal::Device)?;
    let tessellator = Tessellator::new(&device);
    match selftest::run(&device, &queue, &tessellator) {
        Ok(None) => Ok((device, queue, tessellator)),
        Ok(Some(fault)) => Err(Refusal::Fault(fault)),
        Err(e) => Err(Refusal::SelfTest(e)),
    }
}

/// Why an adapter was refused.
#[derive(Debug, thiserror::Error)]
enum Refusal {
    /// Its device could not be opened.
    #[error("{0}")]
    Device(GpuError),
    /// A kernel gave a wrong value (the fault names kernel, degree and values).
    #[error("{0}")]
    Fault(selftest::KernelFault),
    /// The self-test could not run.
    #[error("kernel self-test failed: {0}")]
    SelfTest(GpuError),
}

/// Opens `adapter`'s device with its own limits and timestamp queries when it has them.
fn open_device(adapter: &wgpu::Adapter) -> Result<(wgpu::Device, wgpu::Queue), GpuError> {
    let wanted_features = wgpu::Features::TIMESTAMP_QUERY;
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("splinescope"),
        required_features: adapter.features() & wanted_features,
        required_limits: adapter.limits(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .map_err(|e| GpuError::Device(e.to_string()))
}

/// A one-line description of an adapter: name, type, backend, driver.
#[must_use]
pub fn describe_adapter(info: &wgpu::AdapterInfo) -> String {
    format!(
        "{} ({:?}, {:?}{}{})",
        info.name,
        info.device_type,
        info.backend,
        if info.driver.is_empty() { "" } else { ", " },
        info.driver
    )
}

impl GpuContext {
    /// A context for offscreen work (no window), with the compute pipelines built on its
    /// device (the fixed-count ones are those the self-test checked).
    ///
    /// # Errors
    /// [`GpuError::NoAdapter`] with an installation hint, or the device request's error.
    pub fn new(opts: &ContextOptions) -> Result<(GpuContext, Pipelines), GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: opts.backend.backends(),
            ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
        });
        Self::with_instance(instance, opts, None)
    }

    /// A context from an existing instance, choosing an adapter that can present to
    /// `surface` when one is given, with the compute pipelines built on its device.
    ///
    /// # Errors
    /// [`GpuError::NoAdapter`] with an installation hint, or the device request's error.
    pub fn with_instance(
        instance: wgpu::Instance,
        opts: &ContextOptions,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<(GpuContext, Pipelines), GpuError> {
        let backends = opts.backend.backends();
        let all = pollster::block_on(instance.enumerate_adapters(backends));
        let seen: Vec<String> = all
            .iter()
            .map(|a| describe_adapter(&a.get_info()))
            .collect();
        let wanted = opts.adapter_name.as_ref().map(|n| n.to_lowercase());
        let mut candidates: Vec<wgpu::Adapter> = all
            .into_iter()
            .filter(|a| surface.is_none_or(|s| a.is_surface_supported(s)))
            .filter(|a| {
                wanted
                    .as_ref()
                    .is_none_or(|w| a.get_info().name.to_lowercase().contains(w))
            })
            .collect();
        candidates.sort_by_key(|a| preference(&a.get_info()));
        if candidates.is_empty() {
            return Err(GpuError::NoAdapter {
                backends: backend_names(backends),
                wanted: opts.adapter_name.clone(),
                seen: if seen.is_empty() {
                    "none".into()
                } else {
                    seen.join("; ")
                },
            });
        }
        // The best adapter whose device opens and whose kernels pass the self-test; a
        // refused adapter is reported only when no other one works.
        let mut refused = Vec::new();
        for adapter in candidates {
            match open_and_test(&adapter) {
                Ok((device, queue, tessellator)) => {
                    let health = watch(&device);
                    let pipelines = Pipelines::with_tessellator(&device, tessellator);
                    let context = GpuContext {
                        instance,
                        adapter,
                        device,
                        queue,
                        health,
                    };
                    return Ok((context, pipelines));
                }
                Err(why) => {
                    refused.push(format!("{}: {why}", describe_adapter(&adapter.get_info())))
                }
            }
        }
        Err(GpuError::Refused {
            reasons: refused.join("; "),
        })
    }

    /// Whether the device is still usable: `Err` once it was lost or reported an error
    /// that no error scope caught (a validation error, running out of memory). Work done
    /// after that point is not trusted: offscreen commands fail with this error and the
    /// viewer stops with it, instead of crashing (wgpu's default is to panic) or showing
    /// garbage.
    ///
    /// # Errors
    /// [`GpuError::DeviceLost`] with the device's message.
    pub fn check_health(&self) -> Result<(), GpuError> {
        match self
            .health
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .as_ref()
        {
            Some(message) => Err(GpuError::DeviceLost(message.clone())),
            None => Ok(()),
        }
    }

    /// A one-line description of the adapter in use.
    #[must_use]
    pub fn describe(&self) -> String {
        describe_adapter(&self.adapter.get_info())
    }

    /// The largest buffer one storage binding may use on this device.
    #[must_use]
    pub fn max_binding_bytes(&self) -> u64 {
        let l = self.device.limits();
        l.max_storage_buffer_binding_size.min(l.max_buffer_size)
    }
}
