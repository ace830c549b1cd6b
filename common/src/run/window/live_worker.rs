//! The web page's reference worker: the lesson's `main` run in a Web
//! Worker ([`super::live_page`] starts it) serves reference jobs instead
//! of opening a window. It loads the lesson's scene from the page's own
//! flags, then answers each job as the desktop's worker thread does
//! ([`Server`]): coarse for a new view, full when the page says the view
//! is still on screen.

use std::cell::RefCell;
use std::rc::Rc;

use anyhow::{anyhow, Result};
use clap::Parser;
use js_sys::{Array, Float32Array, Reflect, Uint32Array, Uint8Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use super::live::Answer;
use super::live_message::{AnswerHeader, JobHeader};
use super::live_page::object;
use super::live_server::Server;
use crate::run::cli::Args;
use crate::run::instruments::Instruments;
use crate::scene::Scene;

/// Whether this module runs in a worker (no page, no canvas).
pub fn in_worker() -> bool {
    js_sys::global()
        .dyn_into::<web_sys::DedicatedWorkerGlobalScope>()
        .is_ok()
}

/// Loads the scene and takes over the worker's messages; every failure,
/// a panic included, goes back to the page as one line.
pub fn serve<L: Instruments>() {
    std::panic::set_hook(Box::new(|info| {
        post_error(&format!("the reference worker panicked: {info}"));
    }));
    if let Err(e) = try_serve::<L>() {
        post_error(&format!("{e:#}"));
    }
}

fn try_serve<L: Instruments>() -> Result<()> {
    let global = scope();
    let flags = Reflect::get(&global, &"workbookArgs".into())
        .ok()
        .and_then(|v| v.as_string())
        .unwrap_or_default();
    let argv = std::iter::once(L::NAME).chain(flags.split_whitespace());
    let args = Args::try_parse_from(argv).map_err(|e| anyhow!("data-args: {e}"))?;
    let scene = crate::run::app::load_scene::<L>(&args)?;
    let server = Rc::new(RefCell::new((Server::default(), scene)));
    let on_message =
        Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
            let (server, scene) = &mut *server.borrow_mut();
            if let Err(e) = handle(server, scene, &e.data()) {
                post_error(&format!("{e:#}"));
            }
        });
    global.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    // The worker lives as long as the page's lesson: so does its handler.
    on_message.forget();
    post(&object(&[("kind", "ready".into())]), &Array::new());
    Ok(())
}

/// One message from the page: a job, or the verdict on the job whose
/// coarse answer went back (`full`, `drop`).
fn handle(server: &mut Server, scene: &Scene, data: &JsValue) -> Result<()> {
    let field = |name: &str| Reflect::get(data, &name.into()).unwrap_or(JsValue::UNDEFINED);
    match field("kind").as_string().as_deref() {
        Some("job") => {
            let header: JobHeader =
                serde_json::from_str(&field("header").as_string().unwrap_or_default())?;
            let id = (field("id").dyn_into::<Uint32Array>())
                .map_err(|_| anyhow!("a job came without its ids"))?
                .to_vec();
            let visibility = Array::from(&field("visibility"))
                .iter()
                .map(|v| v.dyn_into::<Float32Array>().map(|v| v.to_vec()))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|_| anyhow!("a job came without its visibility"))?;
            let job = header.into_job(scene, id, visibility)?;
            answer(server.take(job)?)
        }
        Some("full") => answer(server.full()?),
        Some("drop") => {
            server.drop_waiting();
            Ok(())
        }
        other => Err(anyhow!("the reference worker was sent {other:?}")),
    }
}

/// An answer back to the page, its images moved.
fn answer(a: Answer) -> Result<()> {
    let header = serde_json::to_string(&AnswerHeader::of(&a))?;
    let diff = Uint8Array::from(&a.diff.into_raw()[..]);
    let dv = Uint8Array::from(&a.dv.into_raw()[..]);
    let moved = Array::of2(&diff.buffer(), &dv.buffer());
    let msg = object(&[
        ("kind", "answer".into()),
        ("header", header.into()),
        ("diff", diff.into()),
        ("dv", dv.into()),
    ]);
    post(&msg, &moved);
    Ok(())
}

fn scope() -> web_sys::DedicatedWorkerGlobalScope {
    js_sys::global().unchecked_into()
}

fn post(msg: &JsValue, moved: &Array) {
    if let Err(e) = scope().post_message_with_transfer(msg, moved) {
        web_sys::console::error_1(&format!("the reference worker cannot answer: {e:?}").into());
    }
}

fn post_error(line: &str) {
    post(
        &object(&[("kind", "error".into()), ("text", line.into())]),
        &Array::new(),
    );
}
