//! Opening the device in a web page: the browser's WebGPU, on the page's
//! canvas (the web build, [`crate::run::web`]). The desktop opens it with
//! [`Gpu::open`], which blocks on the adapter; a page must await it.

use anyhow::{anyhow, Result};

use super::{buffer_cap, device_failure, DepthFormatChoice, Gpu, OPTIONAL_FEATURES};

/// The page's element for a lesson's error line.
pub const ERROR_ID: &str = "workbook-error";

/// `line` in the page's error element ([`ERROR_ID`]) and the console: how
/// the web build says what stopped a lesson.
pub fn page_error(line: &str) {
    web_sys::console::error_1(&line.into());
    let element = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(ERROR_ID));
    if let Some(el) = element {
        el.set_text_content(Some(line));
    }
}

/// What the page says when the browser has no WebGPU adapter.
pub const NO_WEBGPU: &str = "this browser offers no WebGPU adapter: the live lessons need a browser with WebGPU (Chrome or Edge 113+, Firefox 141+ on Windows, Safari 26+); the screenshot stays";

impl Gpu {
    /// The browser's WebGPU adapter and a device on it, and a surface on
    /// `canvas`. The same optional features as the desktop, where the
    /// browser offers them; the depth format is the default choice.
    pub async fn open_web(
        canvas: web_sys::HtmlCanvasElement,
    ) -> Result<(Gpu, wgpu::Surface<'static>)> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::BROWSER_WEBGPU;
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
            .map_err(|e| anyhow!("cannot draw to the page's canvas: {e}"))?;
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: Some(&surface),
                ..Default::default()
            })
            .await
            .map_err(|_| anyhow!("{NO_WEBGPU}"))?;
        let mut info = adapter.get_info();
        // WebGPU gives wgpu no adapter name: the page asks the browser.
        if info.name.is_empty() {
            info.name = browser_adapter_name()
                .await
                .unwrap_or_else(|| "WebGPU".into());
        }
        let features = adapter.features() & OPTIONAL_FEATURES;
        let depth_format =
            DepthFormatChoice::Auto.resolve(features, "the web build", &info.name)?;
        let limits = buffer_cap(adapter.limits())?;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("workbook device"),
                required_features: features,
                required_limits: limits,
                ..Default::default()
            })
            .await
            .map_err(|e| anyhow!("{}", device_failure(&info, &e)))?;
        // As on the desktop, a validation error is a lesson's bug: the
        // page shows it as its error line.
        device.on_uncaptured_error(std::sync::Arc::new(|e: wgpu::Error| {
            let line = e
                .to_string()
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            page_error(&format!("error: wgpu: {line}"));
        }));
        Ok((
            Gpu {
                instance,
                adapter,
                device,
                queue,
                info,
                features,
                depth_format,
            },
            surface,
        ))
    }
}

/// The browser's own words for its adapter (`GPUAdapter.info`: vendor,
/// architecture, description), e.g. "google swiftshader".
async fn browser_adapter_name() -> Option<String> {
    use js_sys::Reflect;
    use wasm_bindgen::JsCast;
    let navigator = web_sys::window()?.navigator();
    let gpu = Reflect::get(&navigator, &"gpu".into()).ok()?;
    let request: js_sys::Function = Reflect::get(&gpu, &"requestAdapter".into())
        .ok()?
        .dyn_into()
        .ok()?;
    let promise: js_sys::Promise = request.call0(&gpu).ok()?.dyn_into().ok()?;
    let adapter = wasm_bindgen_futures::JsFuture::from(promise).await.ok()?;
    let info = Reflect::get(&adapter, &"info".into()).ok()?;
    let words: Vec<String> = ["vendor", "architecture", "description"]
        .iter()
        .filter_map(|k| Reflect::get(&info, &(*k).into()).ok()?.as_string())
        .filter(|w| !w.is_empty())
        .collect();
    (!words.is_empty()).then(|| words.join(" "))
}
