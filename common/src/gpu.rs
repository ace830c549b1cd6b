//! Picking an adapter and opening a device.
//!
//! The workbook must run on a laptop GPU and on a machine with no GPU at all:
//! Mesa's lavapipe (Vulkan) and llvmpipe (GL) are software rasterisers that
//! behave like real hardware for everything taught here.

use anyhow::{anyhow, bail, Result};

/// Optional features a lesson can use when the adapter has them.
pub const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::DEPTH_CLIP_CONTROL
    .union(wgpu::Features::DEPTH32FLOAT_STENCIL8)
    .union(wgpu::Features::TIMESTAMP_QUERY)
    .union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    .union(wgpu::Features::PIPELINE_STATISTICS_QUERY);

/// What a learner installs when no adapter is found (one line, printed on exit).
pub const NO_ADAPTER_HINT: &str = "no GPU adapter found: on Debian/Ubuntu install Mesa's software \
drivers with `apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1` (lavapipe/llvmpipe), \
or pass --backend gl";

/// The device and what it can do.
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub features: wgpu::Features,
}

/// Parses a `--backend` value (also used for `WGPU_BACKEND`).
pub fn parse_backend(name: &str) -> Result<wgpu::Backends> {
    match name.trim().to_ascii_lowercase().as_str() {
        "vulkan" | "vk" => Ok(wgpu::Backends::VULKAN),
        "gl" | "gles" | "opengl" => Ok(wgpu::Backends::GL),
        "metal" | "mtl" => Ok(wgpu::Backends::METAL),
        "dx12" | "d3d12" => Ok(wgpu::Backends::DX12),
        other => bail!("--backend: unknown backend {other:?} (expected vulkan, gl, metal or dx12)"),
    }
}

impl Gpu {
    /// Opens a device. `backend` (from `--backend`) wins over `WGPU_BACKEND`.
    /// `display` is the window system connection in windowed mode (GL needs it).
    pub fn new(
        backend: Option<&str>,
        display: Option<Box<dyn wgpu::wgt::WgpuHasDisplayHandle>>,
    ) -> Result<Gpu> {
        let backends = match backend {
            Some(b) => parse_backend(b)?,
            None => match std::env::var("WGPU_BACKEND") {
                Ok(v) if !v.trim().is_empty() => {
                    parse_backend(&v).map_err(|e| anyhow!("WGPU_BACKEND: {e}"))?
                }
                _ => {
                    wgpu::Backends::VULKAN
                        | wgpu::Backends::GL
                        | wgpu::Backends::METAL
                        | wgpu::Backends::DX12
                }
            },
        };
        // Mesa's loaders probe for Wayland and print a line when
        // XDG_RUNTIME_DIR is unset (containers, CI): point it somewhere harmless.
        if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
            std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir());
        }
        // Try the primary APIs first and GL last: probing GL/EGL is slower
        // and noisier, and Vulkan (lavapipe) has the optional features.
        let mut found = None;
        let mut display = display;
        for tier in [
            backends & !wgpu::Backends::GL,
            backends & wgpu::Backends::GL,
        ] {
            if tier.is_empty() {
                continue;
            }
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = tier;
            desc.flags = wgpu::InstanceFlags::from_build_config().with_env();
            desc.display = display.take();
            let instance = wgpu::Instance::new(desc);
            let options = wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                ..Default::default()
            };
            if let Ok(adapter) = pollster::block_on(instance.request_adapter(&options)) {
                found = Some((instance, adapter));
                break;
            }
        }
        let (instance, adapter) = found.ok_or_else(|| anyhow!("{NO_ADAPTER_HINT}"))?;
        let info = adapter.get_info();
        let features = adapter.features() & OPTIONAL_FEATURES;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("workbook device"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| anyhow!("cannot open a device on {}: {e}", info.name))?;
        // Validation errors are programming errors in a lesson; make them one clear line.
        device.on_uncaptured_error(std::sync::Arc::new(|e: wgpu::Error| {
            eprintln!(
                "error: wgpu: {}",
                e.to_string()
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" ")
            );
            std::process::exit(3);
        }));
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            info,
            features,
        })
    }

    pub fn has(&self, f: wgpu::Features) -> bool {
        self.features.contains(f)
    }

    /// `"llvmpipe (LLVM 15.0.6, 256 bits)"`, as the report names it.
    pub fn adapter_name(&self) -> String {
        self.info.name.clone()
    }

    /// `"Vulkan"`, `"Gl"`, ...
    pub fn backend_name(&self) -> String {
        format!("{:?}", self.info.backend)
    }

    /// The depth-stencil format for stencil lessons: 32-bit float depth when
    /// the adapter has it, else the always-available 24-bit.
    pub fn depth_stencil_format(&self) -> wgpu::TextureFormat {
        if self.has(wgpu::Features::DEPTH32FLOAT_STENCIL8) {
            wgpu::TextureFormat::Depth32FloatStencil8
        } else {
            wgpu::TextureFormat::Depth24PlusStencil8
        }
    }

    /// Blocks until the GPU has finished everything submitted so far.
    pub fn wait(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| anyhow!("GPU wait failed: {e}"))?;
        Ok(())
    }
}
