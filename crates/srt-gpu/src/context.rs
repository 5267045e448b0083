//! Headless GPU access: instance, adapter and device, with wgpu validation errors turned into
//! Rust errors instead of panics.

use std::io::Write as _;
use std::sync::{Arc, Mutex, OnceLock};

use crate::error::GpuError;
use crate::formats::{COLOR_FORMAT, FALLBACK_COLOR_FORMAT};
use crate::pipelines::{Pipelines, Varyings};

/// The API of a software rasteriser ([`GpuContext::software_api`]): what its start-up costs
/// depend on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SoftwareApi {
    /// Vulkan (Mesa's lavapipe, SwiftShader's Vulkan).
    Vulkan,
    /// OpenGL through EGL (Mesa's llvmpipe).
    Gl,
    /// Any other (WARP on Direct3D 12, a browser's fallback adapter).
    Other,
}

/// A device and queue, plus facts about the adapter.
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name, driver and backend.
    pub adapter_info: wgpu::AdapterInfo,
    /// Whether GPU timestamp queries are available (for benchmarks).
    pub timestamps: bool,
    /// The colour format renderers draw into on this device.
    pub color_format: wgpu::TextureFormat,
    /// Whether draws may take their counts from GPU buffers (`draw_indirect`; every Vulkan,
    /// Metal and DX12 adapter, OpenGL from 4.3 / ES 3.1, not WebGL 2).
    pub indirect_draws: bool,
    /// How the object passes carry a draw's data to their fragments ([`Varyings::for_adapter`]
    /// of the adapter; a test may choose the other: renderers made afterwards use it).
    pub varyings: Varyings,
    errors: Arc<Mutex<Vec<String>>>,
    /// The device's pipelines by moving lights and varyings ([`GpuContext::pipelines`]).
    pipelines: [OnceLock<Arc<Pipelines>>; 4],
}

impl GpuContext {
    /// Opens the first adapter wgpu finds (high performance preferred; software adapters such
    /// as lavapipe and llvmpipe count). `WGPU_BACKEND`, `WGPU_ADAPTER_NAME` and the other
    /// `WGPU_*` variables select backends and adapters as wgpu documents.
    ///
    /// # Errors
    /// [`GpuError::NoAdapter`] when there is none, [`GpuError::Device`] when it fails.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async(|limits| limits))
    }

    /// Opens the adapter [`GpuContext::new`] would, with the device's limits passed through
    /// `tighten` (e.g. WebGPU's default 128 MiB storage bindings on an adapter that allows more,
    /// or smaller ones to see how srt splits a scene to fit): a way to try what a smaller
    /// device draws. Limits can only be lowered: the adapter refuses more than it has.
    ///
    /// # Errors
    /// As [`GpuContext::new`].
    pub fn with_limits(
        tighten: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async(tighten))
    }

    async fn new_async(
        tighten: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<Self, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle().with_env());
        let adapter = match wgpu::util::initialize_adapter_from_env(&instance, None).await {
            Ok(adapter) => adapter,
            Err(_) => instance
                .request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::HighPerformance,
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    ..Default::default()
                })
                .await
                .map_err(|_| GpuError::NoAdapter)?,
        };
        let mut descriptor = device_descriptor(&adapter);
        descriptor.required_limits = tighten(descriptor.required_limits);
        Self::open(&adapter, &descriptor).await
    }

    /// Opens a device on `adapter` with the features srt uses where available.
    ///
    /// # Errors
    /// [`GpuError::Device`] when the adapter refuses.
    pub async fn from_adapter(adapter: &wgpu::Adapter) -> Result<Self, GpuError> {
        Self::open(adapter, &device_descriptor(adapter)).await
    }

    /// Opens a device described by `descriptor` on `adapter`.
    async fn open(
        adapter: &wgpu::Adapter,
        descriptor: &wgpu::DeviceDescriptor<'_>,
    ) -> Result<Self, GpuError> {
        let (device, queue) =
            adapter
                .request_device(descriptor)
                .await
                .map_err(|e| GpuError::Device {
                    adapter: adapter.get_info().name,
                    reason: e.to_string(),
                })?;
        Ok(Self::from_device(device, queue, adapter))
    }

    /// Wraps a device that someone else opened on `adapter` (e.g. the viewer's window system),
    /// so the renderer can draw with it.
    #[must_use]
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, adapter: &wgpu::Adapter) -> Self {
        let adapter_info = adapter.get_info();
        let indirect_draws = adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::INDIRECT_EXECUTION);
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let color_format = if adapter_info.backend == wgpu::Backend::Gl {
            FALLBACK_COLOR_FORMAT
        } else {
            COLOR_FORMAT
        };
        let varyings = Varyings::for_adapter(adapter_info.device_type);
        let errors = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&errors);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            sink.lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .push(error.to_string());
        }));
        // A lost device (driver reset, GPU removed) surfaces as an error of the next frame.
        let lost = Arc::clone(&errors);
        device.set_device_lost_callback(move |reason, message| {
            if reason != wgpu::DeviceLostReason::Destroyed {
                lost.lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner)
                    .push(format!("the GPU device was lost ({reason:?}): {message}"));
            }
        });
        Self {
            device,
            queue,
            adapter_info,
            timestamps,
            color_format,
            indirect_draws,
            varyings,
            errors,
            pipelines: [(); 4].map(|()| OnceLock::new()),
        }
    }

    /// The device's pipelines for scenes without or with (`lit`) moving lights, with the
    /// context's [`GpuContext::varyings`], made by the first renderer that asks and shared by
    /// every later renderer of this context, so that a new scene (the viewer's reload, each
    /// case of `cargo xtask bench` and `validate`) does not compile them again.
    pub(crate) fn pipelines(&self, lit: bool) -> Arc<Pipelines> {
        let varyings = self.varyings;
        let index = usize::from(lit) + 2 * usize::from(varyings == Varyings::Lean);
        Arc::clone(self.pipelines[index].get_or_init(|| {
            Arc::new(Pipelines::new(
                &self.device,
                self.color_format,
                lit,
                varyings,
            ))
        }))
    }

    /// The API this adapter is reached through if it is a software rasteriser running on the
    /// CPU (Mesa's lavapipe and llvmpipe, SwiftShader, WARP); `None` for a GPU.
    #[must_use]
    pub fn software_api(&self) -> Option<SoftwareApi> {
        (self.adapter_info.device_type == wgpu::DeviceType::Cpu).then_some(
            match self.adapter_info.backend {
                wgpu::Backend::Vulkan => SoftwareApi::Vulkan,
                wgpu::Backend::Gl => SoftwareApi::Gl,
                _ => SoftwareApi::Other,
            },
        )
    }

    /// A one-line description of the adapter: name, backend and device type.
    #[must_use]
    pub fn adapter_summary(&self) -> String {
        let info = &self.adapter_info;
        format!(
            "{} ({:?}, {:?}, driver {})",
            info.name, info.backend, info.device_type, info.driver
        )
    }

    /// Takes the wgpu errors reported since the last call.
    ///
    /// # Errors
    /// [`GpuError::Wgpu`] listing them, if there were any.
    pub fn take_errors(&self) -> Result<(), GpuError> {
        let mut errors = self
            .errors
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if errors.is_empty() {
            Ok(())
        } else {
            Err(GpuError::Wgpu(std::mem::take(&mut *errors).join("; ")))
        }
    }

    /// Waits until the queue is idle.
    ///
    /// # Errors
    /// [`GpuError::Readback`] if polling fails (device lost).
    pub fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Readback(e.to_string()))
    }

    /// Reads a buffer created with `MAP_READ` back to memory.
    ///
    /// # Errors
    /// [`GpuError::Readback`] when mapping fails.
    pub fn read_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        self.read_buffer_with(buffer, <[u8]>::to_vec)
    }

    /// Maps `buffer` (whole) for reading once the GPU is idle and hands its bytes to `read`,
    /// without copying them first (an image's readback is tens of megabytes).
    ///
    /// # Errors
    /// [`GpuError::Readback`] when mapping fails.
    pub fn read_buffer_with<T>(
        &self,
        buffer: &wgpu::Buffer,
        read: impl FnOnce(&[u8]) -> T,
    ) -> Result<T, GpuError> {
        let slice = buffer.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        self.wait()?;
        receiver
            .recv()
            .map_err(|e| GpuError::Readback(e.to_string()))?
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        let value = read(
            &slice
                .get_mapped_range()
                .map_err(|e| GpuError::Readback(e.to_string()))?,
        );
        buffer.unmap();
        Ok(value)
    }
}

/// The device srt asks `adapter` for: the adapter's own buffer and texture limits (large
/// models need them), timestamp queries where available (for `cargo xtask bench`), and early
/// depth tests where available ([`crate::shaders::ConservativeDepth`]).
#[must_use]
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    let limits = adapter.limits();
    let optional = adapter.features()
        & (wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::SHADER_EARLY_DEPTH_TEST);
    wgpu::DeviceDescriptor {
        label: Some("srt"),
        required_features: optional,
        required_limits: wgpu::Limits {
            max_storage_buffer_binding_size: limits.max_storage_buffer_binding_size,
            max_buffer_size: limits.max_buffer_size,
            max_storage_buffers_per_shader_stage: limits
                .max_storage_buffers_per_shader_stage
                .min(8),
            ..wgpu::Limits::downlevel_defaults().using_resolution(limits.clone())
        },
        ..Default::default()
    }
}

/// For tests: the GPU context, or `None` after printing a visible skip line — unless
/// `SRT_REQUIRE_GPU=1`, in which case a missing adapter is a panic (a failed test).
///
/// # Panics
/// When no adapter exists and `SRT_REQUIRE_GPU=1`.
#[must_use]
pub fn context_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::new() {
        Ok(context) => Some(context),
        Err(error) => {
            if std::env::var("SRT_REQUIRE_GPU").is_ok_and(|v| v == "1") {
                panic!("{test}: SRT_REQUIRE_GPU=1 but the GPU is unavailable: {error}");
            }
            // Written to the process's stderr directly: the test harness captures `eprintln!`
            // of passing tests, and a skip must be visible.
            let _ = writeln!(
                std::io::stderr(),
                "SKIPPED {test}: no GPU adapter ({error}); set SRT_REQUIRE_GPU=1 to make this a failure"
            );
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renderers_of_a_context_share_its_pipelines_by_lights_and_varyings() {
        let Some(mut ctx) =
            context_or_skip("renderers_of_a_context_share_its_pipelines_by_lights_and_varyings")
        else {
            return;
        };
        let plain = ctx.pipelines(false);
        assert!(Arc::ptr_eq(&plain, &ctx.pipelines(false)));
        assert!(!Arc::ptr_eq(&plain, &ctx.pipelines(true)));
        let other = match ctx.varyings {
            Varyings::Flat => Varyings::Lean,
            Varyings::Lean => Varyings::Flat,
        };
        ctx.varyings = other;
        let switched = ctx.pipelines(false);
        assert!(!Arc::ptr_eq(&plain, &switched));
        assert!(Arc::ptr_eq(&switched, &ctx.pipelines(false)));
    }
}
