//! Picking an adapter and opening a device.
//!
//! The workbook must run on a laptop GPU and on a machine with no GPU at all:
//! Mesa's lavapipe (Vulkan) and llvmpipe (GL) are software rasterisers that
//! behave like real hardware for everything taught here.
//!
//! The GPU and what is drawn, one module a concept:
//! - [`render`]: the scene on the GPU, the shader prelude, the base pass.
//! - [`lit`]: the lit pass that adds one light.
//! - [`bindings`]: bind group layouts and groups (textures, samplers, uniforms).
//! - [`chapter_copy`]: the half of a chapter copy a grading run compiles.
//! - [`targets`]: the frame's render targets and texture helpers.
//! - [`fullscreen`]: the full-screen triangle (blits, readback, markers).
//! - [`readback`]: buffers, textures and query results back to the CPU.
//! - [`pending_read`]: one copy on its way back, read without blocking.
//! - [`read_later`]: code that reads textures back, run where nothing may
//!   wait (a web page): each read comes back a frame or more later.
//! - [`depth_probe`]: what a depth format really stores (24-bit unorm or float).
//! - [`wgsl`]: a WGSL module built from named files, its errors mapped back
//!   to the file, line and column they came from.
//! - [`choice`]: which adapter, backend and depth format to open (flags, variables).
//! - [`web`]: the device in a web page, on the browser's WebGPU (the web build).
//! - [`watchdog`]: a frame the GPU does not finish in time ends the run.

pub mod bindings;
pub mod chapter_copy;
pub mod choice;
pub mod depth_probe;
pub mod fullscreen;
pub mod lit;
pub mod pending_read;
pub mod read_later;
pub mod readback;
pub mod render;
pub mod targets;
pub mod watchdog;
#[cfg(target_arch = "wasm32")]
pub mod web;
pub mod wgsl;

use anyhow::{anyhow, Result};

pub use choice::{parse_backend, AdapterChoice, DepthFormatChoice, NO_SOFTWARE_ADAPTER_HINT};

/// `limits` with `WORKBOOK_MAX_BUFFER_SIZE` (bytes), if set, as the
/// largest buffer and storage binding: a smaller GPU's room on this one,
/// to see what a lesson leaves out there (lesson 05's routes).
pub fn buffer_cap(mut limits: wgpu::Limits) -> Result<wgpu::Limits> {
    let Ok(v) = std::env::var("WORKBOOK_MAX_BUFFER_SIZE") else {
        return Ok(limits);
    };
    let cap: u64 = v.trim().parse().map_err(|_| {
        anyhow!(
            "WORKBOOK_MAX_BUFFER_SIZE = {:?}: give a size in bytes, such as 134217728",
            v
        )
    })?;
    limits.max_buffer_size = limits.max_buffer_size.min(cap);
    limits.max_storage_buffer_binding_size = limits.max_storage_buffer_binding_size.min(cap);
    Ok(limits)
}

/// The line for a device that would not open. wgpu's GL backend fails on
/// NVIDIA's drivers ("Parent device is lost", gfx-rs/wgpu#7068, seen on an
/// H100): that case names the issue and the backend that works.
pub fn device_failure(info: &wgpu::AdapterInfo, e: &dyn std::fmt::Display) -> String {
    let line = format!(
        "cannot open a device on {} ({:?}): {e}",
        info.name, info.backend
    );
    let nvidia = info.vendor == NVIDIA_VENDOR_ID || info.name.to_uppercase().contains("NVIDIA");
    if info.backend == wgpu::Backend::Gl && nvidia {
        format!(
            "{line}; wgpu's GL backend cannot open NVIDIA's driver (gfx-rs/wgpu#7068): use --backend vulkan"
        )
    } else {
        line
    }
}

/// The PCI vendor id of NVIDIA.
const NVIDIA_VENDOR_ID: u32 = 0x10de;

/// Optional features a lesson can use when the adapter has them.
pub const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::DEPTH_CLIP_CONTROL
    .union(wgpu::Features::DEPTH32FLOAT_STENCIL8)
    .union(wgpu::Features::TIMESTAMP_QUERY)
    .union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    .union(wgpu::Features::PIPELINE_STATISTICS_QUERY);

/// What a learner installs when no adapter is found (one line, printed on exit).
pub const NO_ADAPTER_HINT: &str = "no GPU adapter found: on Linux without a GPU driver, install Mesa's \
software rasterisers (lavapipe/llvmpipe) with `apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1`, \
or pass --backend gl; Windows (DX12, Vulkan) and macOS (Metal) use their GPU, with nothing to install";

/// The device and what it can do.
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub features: wgpu::Features,
    /// The scene's depth-stencil format ([`Gpu::depth_stencil_format`]).
    depth_format: wgpu::TextureFormat,
}

impl Gpu {
    /// Opens a device. `backend` (from `--backend`) wins over `WGPU_BACKEND`,
    /// `adapter` (from `--adapter`) over `WORKBOOK_ADAPTER`.
    /// `display` is the window system connection in windowed mode (GL needs it).
    /// The scene's depth format follows `WORKBOOK_DEPTH_FORMAT` ([`Gpu::open`]).
    pub fn new(
        backend: Option<&str>,
        adapter: Option<&str>,
        display: Option<Box<dyn wgpu::wgt::WgpuHasDisplayHandle>>,
    ) -> Result<Gpu> {
        Gpu::open(backend, adapter, None, display)
    }

    /// [`Gpu::new`], and `depth_format` (from `--depth-format`) wins over
    /// `WORKBOOK_DEPTH_FORMAT` for the scene's depth-stencil format.
    pub fn open(
        backend: Option<&str>,
        adapter: Option<&str>,
        depth_format: Option<&str>,
        display: Option<Box<dyn wgpu::wgt::WgpuHasDisplayHandle>>,
    ) -> Result<Gpu> {
        let choice = AdapterChoice::from_flag_or_env(adapter)?;
        watchdog::limit()?;
        let (depth_choice, depth_source) = DepthFormatChoice::from_flag_or_env(depth_format)?;
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
            // The window's display handle is for GL (EGL presents only on
            // the display it was opened on); Vulkan and the others need none.
            if tier.contains(wgpu::Backends::GL) {
                desc.display = display.take();
            }
            let instance = wgpu::Instance::new(desc);
            let adapter = if choice == AdapterChoice::Any {
                let options = wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::HighPerformance,
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    ..Default::default()
                };
                pollster::block_on(instance.request_adapter(&options)).ok()
            } else {
                let all = pollster::block_on(instance.enumerate_adapters(tier));
                all.into_iter().find(|a| choice.accepts(&a.get_info()))
            };
            if let Some(adapter) = adapter {
                found = Some((instance, adapter));
                break;
            }
        }
        let (instance, adapter) = found.ok_or_else(|| match &choice {
            AdapterChoice::Any => anyhow!("{NO_ADAPTER_HINT}"),
            AdapterChoice::Software => anyhow!("{NO_SOFTWARE_ADAPTER_HINT}"),
            AdapterChoice::Named(n) => anyhow!(
                "no GPU adapter found whose name contains {n:?} (--adapter): \
                 `vulkaninfo --summary` lists yours; --adapter any takes the default"
            ),
        })?;
        let info = adapter.get_info();
        let features = adapter.features() & OPTIONAL_FEATURES;
        let depth_format = depth_choice.resolve(features, depth_source, &info.name)?;
        let limits = buffer_cap(adapter.limits())?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("workbook device"),
            required_features: features,
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| anyhow!("{}", device_failure(&info, &e)))?;
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
            depth_format,
        })
    }

    /// Whether this build may wait for the GPU, to read a result back at
    /// once: the desktop may; a web page may not (the web build). Where it
    /// may not, the lessons count nothing (the report's counters, each
    /// read back in its own untimed submit; the page's overlay shows none)
    /// and probe nothing (lesson 07 takes a depth format at its name).
    pub fn can_wait(&self) -> bool {
        !cfg!(target_arch = "wasm32")
    }

    pub fn has(&self, f: wgpu::Features) -> bool {
        self.features.contains(f)
    }

    /// Runs `f` inside an out-of-memory error scope: what `f` returned,
    /// and the error the device reported for it, if any.
    pub fn out_of_memory_scope<R>(&self, f: impl FnOnce() -> R) -> (R, Option<wgpu::Error>) {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let r = f();
        // A web page cannot block on the scope's answer: there an
        // out-of-memory error reaches the device's uncaptured-error
        // handler, which stops the lesson with the error (`run::web`).
        #[cfg(target_arch = "wasm32")]
        return {
            drop(scope);
            (r, None)
        };
        #[cfg(not(target_arch = "wasm32"))]
        (r, pollster::block_on(scope.pop()))
    }

    /// `"llvmpipe (LLVM 15.0.6, 256 bits)"`, as the report names it.
    pub fn adapter_name(&self) -> String {
        self.info.name.clone()
    }

    /// `"Vulkan"`, `"Gl"`, ...
    pub fn backend_name(&self) -> String {
        format!("{:?}", self.info.backend)
    }

    /// The scene's depth-stencil format (the base pass, the stencil
    /// lessons): as `--depth-format` chose, by default 32-bit float depth
    /// when the adapter has it, else the always-available `Depth24PlusStencil8`.
    pub fn depth_stencil_format(&self) -> wgpu::TextureFormat {
        self.depth_format
    }

    /// Blocks until the GPU has finished everything submitted so far, at
    /// most the [`watchdog`]'s limit: past it, the run ends with one line.
    /// In a web page nothing can block: the browser runs what was
    /// submitted in its own time, and this returns at once (a readback
    /// there goes through [`crate::gpu::readback::PendingRead`]).
    pub fn wait(&self) -> Result<()> {
        if cfg!(target_arch = "wasm32") {
            return Ok(());
        }
        watchdog::wait(&self.device)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_format_choice_parses_flag_values_and_wgpu_names() {
        use DepthFormatChoice::*;
        assert_eq!(DepthFormatChoice::parse("auto").unwrap(), Auto);
        let d24 = [
            "depth24plus-stencil8",
            "Depth24PlusStencil8",
            " DEPTH24PLUS_STENCIL8 ",
        ];
        for text in d24 {
            assert_eq!(DepthFormatChoice::parse(text).unwrap(), Depth24PlusStencil8);
        }
        let d32 = DepthFormatChoice::parse("depth32float-stencil8").unwrap();
        assert_eq!(d32, Depth32FloatStencil8);
        let e = DepthFormatChoice::from_flag_or_env(Some("depth16"));
        let e = e.unwrap_err().to_string();
        assert!(e.contains("--depth-format") && e.contains("depth16"), "{e}");
    }

    #[test]
    fn depth32float_without_the_feature_is_one_line_naming_both() {
        use wgpu::TextureFormat as T;
        let (none, d32) = (
            wgpu::Features::empty(),
            wgpu::Features::DEPTH32FLOAT_STENCIL8,
        );
        let resolve = |c: DepthFormatChoice, f| c.resolve(f, "--depth-format", "gpu");
        assert_eq!(
            resolve(DepthFormatChoice::Auto, d32).unwrap(),
            T::Depth32FloatStencil8
        );
        assert_eq!(
            resolve(DepthFormatChoice::Auto, none).unwrap(),
            T::Depth24PlusStencil8
        );
        let d24 = DepthFormatChoice::Depth24PlusStencil8;
        assert_eq!(resolve(d24, d32).unwrap(), T::Depth24PlusStencil8);
        let e = resolve(DepthFormatChoice::Depth32FloatStencil8, none).unwrap_err();
        let e = e.to_string();
        assert!(!e.contains('\n'), "{e}");
        assert!(
            e.contains("--depth-format") && e.contains("DEPTH32FLOAT_STENCIL8"),
            "{e}"
        );
    }

    fn info(name: &str, vendor: u32, backend: wgpu::Backend) -> wgpu::AdapterInfo {
        wgpu::AdapterInfo {
            name: name.into(),
            vendor,
            ..wgpu::AdapterInfo::new(wgpu::DeviceType::DiscreteGpu, backend)
        }
    }

    #[test]
    fn gl_on_nvidia_names_the_wgpu_issue_and_vulkan() {
        let e = "Parent device is lost";
        let gl = device_failure(
            &info("NVIDIA H100 80GB HBM3", 0x10de, wgpu::Backend::Gl),
            &e,
        );
        assert!(
            gl.contains("gfx-rs/wgpu#7068") && gl.contains("--backend vulkan"),
            "{gl}"
        );
        assert!(gl.contains("Parent device is lost"), "{gl}");
        // By name alone (EGL may report no vendor id).
        let by_name = device_failure(
            &info("NVIDIA GeForce RTX 4090/PCIe/SSE2", 0, wgpu::Backend::Gl),
            &e,
        );
        assert!(by_name.contains("gfx-rs/wgpu#7068"), "{by_name}");
        // Vulkan on NVIDIA, or GL elsewhere: no such advice.
        let vk = device_failure(
            &info("NVIDIA H100 80GB HBM3", 0x10de, wgpu::Backend::Vulkan),
            &e,
        );
        let mesa = device_failure(
            &info(
                "llvmpipe (LLVM 15.0.6, 256 bits)",
                0x10005,
                wgpu::Backend::Gl,
            ),
            &e,
        );
        assert!(
            !vk.contains("7068") && !mesa.contains("7068"),
            "{vk}\n{mesa}"
        );
        assert!(
            mesa.starts_with("cannot open a device on llvmpipe"),
            "{mesa}"
        );
    }
}
