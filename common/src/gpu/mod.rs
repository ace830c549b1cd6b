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
//! - [`depth_probe`]: what a depth format really stores (24-bit unorm or float).
//! - [`wgsl`]: a WGSL module built from named files, its errors mapped back
//!   to the file, line and column they came from.

pub mod bindings;
pub mod chapter_copy;
pub mod depth_probe;
pub mod fullscreen;
pub mod lit;
pub mod readback;
pub mod render;
pub mod targets;
pub mod wgsl;

use anyhow::{anyhow, bail, Result};

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

/// Which adapter to open (`--adapter`, else `WORKBOOK_ADAPTER`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AdapterChoice {
    /// The system's preferred (high-performance) adapter: a real GPU if
    /// there is one. The default.
    Any,
    /// A software rasteriser (lavapipe, llvmpipe): what CI pins, so that
    /// its runs repeat to the fragment.
    Software,
    /// The first adapter whose name contains this text (any case).
    Named(String),
}

impl AdapterChoice {
    /// Parses `any`, `software` or a name fragment.
    pub fn parse(text: &str) -> Result<AdapterChoice> {
        match text.trim().to_ascii_lowercase().as_str() {
            "" => bail!("--adapter: empty (expected any, software or part of an adapter's name)"),
            "any" => Ok(AdapterChoice::Any),
            "software" | "cpu" => Ok(AdapterChoice::Software),
            name => Ok(AdapterChoice::Named(name.to_string())),
        }
    }

    /// `--adapter` if given, else `WORKBOOK_ADAPTER`, else [`AdapterChoice::Any`].
    pub fn from_flag_or_env(flag: Option<&str>) -> Result<AdapterChoice> {
        match flag {
            Some(f) => AdapterChoice::parse(f),
            None => match std::env::var("WORKBOOK_ADAPTER") {
                Ok(v) if !v.trim().is_empty() => {
                    AdapterChoice::parse(&v).map_err(|e| anyhow!("WORKBOOK_ADAPTER: {e}"))
                }
                _ => Ok(AdapterChoice::Any),
            },
        }
    }

    fn accepts(&self, info: &wgpu::AdapterInfo) -> bool {
        match self {
            AdapterChoice::Any => true,
            AdapterChoice::Software => info.device_type == wgpu::DeviceType::Cpu,
            AdapterChoice::Named(n) => info.name.to_ascii_lowercase().contains(n),
        }
    }
}

/// Which depth-stencil format the scene uses (`--depth-format`, else
/// `WORKBOOK_DEPTH_FORMAT`). wgpu's `Depth24PlusStencil8` is 24-bit unorm
/// where the driver has it and 32-bit float where it does not, so
/// [`crate::gpu::depth_probe`] asks the adapter what it stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFormatChoice {
    /// `Depth32FloatStencil8` where the adapter has it, else
    /// `Depth24PlusStencil8`. The default.
    Auto,
    Depth24PlusStencil8,
    Depth32FloatStencil8,
}

impl DepthFormatChoice {
    /// Parses `auto`, `depth24plus-stencil8` or `depth32float-stencil8`
    /// (any case; wgpu's names, `Depth24PlusStencil8`, are accepted too).
    pub fn parse(text: &str) -> Result<DepthFormatChoice> {
        let key: String = text
            .trim()
            .to_ascii_lowercase()
            .chars()
            .filter(|c| !matches!(c, '-' | '_'))
            .collect();
        match key.as_str() {
            "auto" => Ok(DepthFormatChoice::Auto),
            "depth24plusstencil8" => Ok(DepthFormatChoice::Depth24PlusStencil8),
            "depth32floatstencil8" => Ok(DepthFormatChoice::Depth32FloatStencil8),
            _ => bail!(
                "unknown depth format {:?} (expected auto, depth24plus-stencil8 or depth32float-stencil8)",
                text.trim()
            ),
        }
    }

    /// `--depth-format` if given, else `WORKBOOK_DEPTH_FORMAT`, else
    /// [`DepthFormatChoice::Auto`]. Also returns where the choice came
    /// from, for error messages.
    pub fn from_flag_or_env(flag: Option<&str>) -> Result<(DepthFormatChoice, &'static str)> {
        match flag {
            Some(f) => DepthFormatChoice::parse(f)
                .map(|c| (c, "--depth-format"))
                .map_err(|e| anyhow!("--depth-format: {e}")),
            None => match std::env::var("WORKBOOK_DEPTH_FORMAT") {
                Ok(v) if !v.trim().is_empty() => DepthFormatChoice::parse(&v)
                    .map(|c| (c, "WORKBOOK_DEPTH_FORMAT"))
                    .map_err(|e| anyhow!("WORKBOOK_DEPTH_FORMAT: {e}")),
                _ => Ok((DepthFormatChoice::Auto, "--depth-format")),
            },
        }
    }

    /// The format on `adapter`, which has `features`; asking for
    /// `Depth32FloatStencil8` where it is missing is an error naming
    /// `source` (the flag or the variable) and the feature.
    pub fn resolve(
        self,
        features: wgpu::Features,
        source: &str,
        adapter: &str,
    ) -> Result<wgpu::TextureFormat> {
        let has_d32 = features.contains(wgpu::Features::DEPTH32FLOAT_STENCIL8);
        Ok(match self {
            DepthFormatChoice::Auto if has_d32 => wgpu::TextureFormat::Depth32FloatStencil8,
            DepthFormatChoice::Auto | DepthFormatChoice::Depth24PlusStencil8 => {
                wgpu::TextureFormat::Depth24PlusStencil8
            }
            DepthFormatChoice::Depth32FloatStencil8 if has_d32 => {
                wgpu::TextureFormat::Depth32FloatStencil8
            }
            DepthFormatChoice::Depth32FloatStencil8 => bail!(
                "{source} depth32float-stencil8: the adapter {adapter} lacks the DEPTH32FLOAT_STENCIL8 feature; use depth24plus-stencil8 or auto"
            ),
        })
    }
}

/// The line printed when `--adapter software` finds none.
pub const NO_SOFTWARE_ADAPTER_HINT: &str = "no GPU adapter found that is a software rasteriser (--adapter software, which CI pins): on Linux install Mesa's lavapipe/llvmpipe with `apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1`; on Windows and macOS, or to use your GPU, pass --adapter any (WORKBOOK_ADAPTER=any), the default";

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

    pub fn has(&self, f: wgpu::Features) -> bool {
        self.features.contains(f)
    }

    /// Runs `f` inside an out-of-memory error scope: what `f` returned,
    /// and the error the device reported for it, if any.
    pub fn out_of_memory_scope<R>(&self, f: impl FnOnce() -> R) -> (R, Option<wgpu::Error>) {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let r = f();
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

    /// Blocks until the GPU has finished everything submitted so far.
    pub fn wait(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| anyhow!("GPU wait failed: {e}"))?;
        Ok(())
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
