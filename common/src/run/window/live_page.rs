//! The live reference in a web page: a Web Worker with its own instance of
//! the module ([`super::live_worker`]), so that the page's thread never
//! waits for a ray cast. It answers as the desktop's worker does
//! ([`super::live`], [`super::live_server`]): a new view is ray cast coarse
//! first, and its full pass follows only if the window's next frame still
//! shows that view, which this side judges and tells the worker.
//!
//! The worker is started from a small module script made here (a `Blob`):
//! it imports the page's glue (the canvas's `data-glue`), instantiates the
//! module the page compiled (`wasm_bindgen::module()`, posted to it, so
//! the worker downloads and compiles nothing), and runs the lesson
//! (`data-lesson`) with the page's flags (`data-args`), which in a worker
//! serves reference jobs instead of opening a window.

use std::cell::RefCell;
use std::rc::Rc;

use anyhow::{anyhow, Result};
use js_sys::{Array, Float32Array, Object, Reflect, Uint32Array, Uint8Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use super::live_job::{Answer, Job, Level, PendingJob};
use super::live_message::{AnswerHeader, JobHeader};
use super::page::canvas;

/// The worker's first script: it starts the module, then the module
/// takes over its messages (`live_worker::serve`).
const BOOT: &str = r#"
self.onmessage = async (e) => {
  const { glue, module, lesson, args } = e.data;
  try {
    const m = await import(glue);
    await m.default({ module_or_path: module });
    self.workbookArgs = args;
    m.run_lesson(lesson);
  } catch (err) {
    self.postMessage({ kind: "error", text: "the reference worker did not start: " + err });
  }
};
"#;

/// What the worker said, not yet read by the window.
#[derive(Default)]
struct Inbox {
    ready: bool,
    answers: Vec<Result<Answer>>,
    failed: Option<String>,
}

/// The worker, and the job it has.
pub struct LiveReference {
    worker: web_sys::Worker,
    inbox: Rc<RefCell<Inbox>>,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::ErrorEvent)>,
    /// A job sent before the worker was ready: posted once it is.
    queued: Option<Job>,
    /// The view of the job under way, and whether its coarse answer came
    /// (it then waits for the window's next frame to say full or drop).
    job: Option<(u64, bool)>,
    arrived: Vec<Answer>,
    failed: Option<anyhow::Error>,
}

impl LiveReference {
    pub fn start() -> Result<Self> {
        let canvas = canvas()?;
        let attr = |name: &str| {
            canvas
                .get_attribute(name)
                .ok_or_else(|| anyhow!("the canvas has no {name} (the page's script sets it)"))
        };
        let (glue, lesson) = (attr("data-glue")?, attr("data-lesson")?);
        let args = canvas.get_attribute("data-args").unwrap_or_default();
        let worker = boot_worker()?;
        let inbox: Rc<RefCell<Inbox>> = Default::default();
        let to = inbox.clone();
        let on_message =
            Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
                receive(&mut to.borrow_mut(), &e.data());
            });
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        let to = inbox.clone();
        let on_error =
            Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(move |e: web_sys::ErrorEvent| {
                to.borrow_mut().failed =
                    Some(format!("the reference worker failed: {}", e.message()));
            });
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        let init = object(&[
            ("glue", glue.into()),
            ("module", wasm_bindgen::module()),
            ("lesson", lesson.into()),
            ("args", args.into()),
        ]);
        worker
            .post_message(&init)
            .map_err(|e| anyhow!("cannot start the reference worker: {e:?}"))?;
        Ok(LiveReference {
            worker,
            inbox,
            _on_message: on_message,
            _on_error: on_error,
            queued: None,
            job: None,
            arrived: Vec::new(),
            failed: None,
        })
    }

    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    /// The view the window's frame draws: a coarse answer waiting for its
    /// verdict gets it (full pass if the view is still this one).
    pub fn note_view(&mut self, scene_gen: u64) {
        self.pump();
        if let Some((gen, true)) = self.job {
            if gen == scene_gen {
                self.post(&object(&[("kind", "full".into())]));
                self.job = Some((gen, false));
            } else {
                self.post(&object(&[("kind", "drop".into())]));
                self.job = None;
            }
        }
    }

    /// Takes a job once [`PendingJob::ready`]: its images copied out of the
    /// mapped buffers here, then moved to the worker.
    pub fn send(&mut self, job: PendingJob) {
        match job.into_job() {
            Ok(job) => {
                self.job = Some((job.stamp.scene_gen, false));
                self.queued = Some(job);
                self.pump();
            }
            Err(e) => self.failed = Some(e),
        }
    }

    /// Whether an answer (or a failure) is waiting to be read.
    pub fn ready(&mut self) -> bool {
        self.pump();
        !self.arrived.is_empty() || self.failed.is_some()
    }

    pub fn answers(&mut self) -> Result<Vec<Answer>> {
        self.pump();
        if let Some(e) = self.failed.take() {
            anyhow::bail!("the live reference failed: {e:#}");
        }
        Ok(self.arrived.drain(..).collect())
    }

    /// Reads what the worker said, and posts the queued job once it is ready.
    fn pump(&mut self) {
        let (ready, answers, failed) = {
            let mut inbox = self.inbox.borrow_mut();
            (
                inbox.ready,
                std::mem::take(&mut inbox.answers),
                inbox.failed.take(),
            )
        };
        if let Some(e) = failed {
            self.failed = Some(anyhow!(e));
            self.job = None;
        }
        for a in answers {
            match a {
                Ok(a) => {
                    if self.job.is_some_and(|(gen, _)| gen == a.stamp.scene_gen) {
                        self.job = match a.level {
                            Level::Coarse => Some((a.stamp.scene_gen, true)),
                            Level::Full => None,
                        };
                    }
                    self.arrived.push(a);
                }
                Err(e) => self.failed = Some(e),
            }
        }
        if ready {
            if let Some(job) = self.queued.take() {
                self.post_job(&job);
            }
        }
    }

    fn post_job(&mut self, job: &Job) {
        let header = match serde_json::to_string(&JobHeader::of(job)) {
            Ok(h) => h,
            Err(e) => {
                self.failed = Some(anyhow!("the reference job: {e}"));
                return;
            }
        };
        let id = Uint32Array::from(&job.frame.id[..]);
        let visibility = Array::new();
        let moved = Array::of1(&id.buffer());
        for v in &job.frame.visibility {
            let v = Float32Array::from(&v[..]);
            moved.push(&v.buffer());
            visibility.push(&v);
        }
        let msg = object(&[
            ("kind", "job".into()),
            ("header", header.into()),
            ("id", id.into()),
            ("visibility", visibility.into()),
        ]);
        if let Err(e) = self.worker.post_message_with_transfer(&msg, &moved) {
            self.failed = Some(anyhow!("cannot send the reference worker its job: {e:?}"));
        }
    }

    fn post(&mut self, msg: &JsValue) {
        if let Err(e) = self.worker.post_message(msg) {
            self.failed = Some(anyhow!("cannot reach the reference worker: {e:?}"));
        }
    }
}

impl Drop for LiveReference {
    fn drop(&mut self) {
        self.worker.terminate();
    }
}

/// The worker, running [`BOOT`].
fn boot_worker() -> Result<web_sys::Worker> {
    let parts = Array::of1(&BOOT.into());
    let options = web_sys::BlobPropertyBag::new();
    options.set_type("text/javascript");
    let blob = web_sys::Blob::new_with_str_sequence_and_options(&parts, &options)
        .map_err(|e| anyhow!("cannot make the reference worker's script: {e:?}"))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)
        .map_err(|e| anyhow!("cannot make the reference worker's script: {e:?}"))?;
    let options = web_sys::WorkerOptions::new();
    options.set_type(web_sys::WorkerType::Module);
    options.set_name("workbook reference");
    let worker = web_sys::Worker::new_with_options(&url, &options)
        .map_err(|e| anyhow!("cannot start the reference worker: {e:?}"))?;
    let _ = web_sys::Url::revoke_object_url(&url);
    Ok(worker)
}

/// One message from the worker, into the inbox.
fn receive(inbox: &mut Inbox, data: &JsValue) {
    let field = |name: &str| Reflect::get(data, &name.into()).unwrap_or(JsValue::UNDEFINED);
    match field("kind").as_string().as_deref() {
        Some("ready") => inbox.ready = true,
        Some("answer") => {
            let bytes = |name: &str| field(name).dyn_into::<Uint8Array>().map(|a| a.to_vec());
            let answer = (|| -> Result<Answer> {
                let header = field("header").as_string().unwrap_or_default();
                let header: AnswerHeader = serde_json::from_str(&header)?;
                let (diff, dv) = (bytes("diff"), bytes("dv"));
                let (Ok(diff), Ok(dv)) = (diff, dv) else {
                    anyhow::bail!("an answer came without its images");
                };
                header.into_answer(diff, dv)
            })();
            inbox.answers.push(answer);
        }
        Some("error") => {
            let text = field("text").as_string().unwrap_or_default();
            inbox.failed = Some(text);
        }
        other => inbox.failed = Some(format!("the reference worker said {other:?}")),
    }
}

/// A plain object with these fields.
pub(super) fn object(fields: &[(&str, JsValue)]) -> JsValue {
    let o = Object::new();
    for (k, v) in fields {
        let _ = Reflect::set(&o, &(*k).into(), v);
    }
    o.into()
}
