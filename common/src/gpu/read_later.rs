//! Results read back a frame or more later, for code written to wait: how
//! a web page gets the lessons' counters and the buffer view, though it
//! may not wait for the GPU.
//!
//! A lesson counts with plain code that submits its counting work and
//! reads a texture or a buffer back ([`super::readback::read_texture`],
//! [`super::readback::read_buffer_copy`]). Called through [`later`] where
//! the thread may not wait (a page), each such read starts its copy and
//! asks for the mapping, and the call stops there ([`NotYet`]: `later`
//! gives `None`). The caller calls the same code again on a later frame
//! (one *attempt* a frame): a read whose copy came back then gives its
//! bytes, and the attempt goes on to its next read or its end. Each read
//! is known by the place that called `later` (its file, line and column)
//! and by how many reads came before it in the attempt (and, to be safe,
//! by its source's size and format): so code that reads one texture twice
//! gets each read's own copy, two callers that read the same texture get
//! their own, and code that makes its scratch textures anew each attempt
//! finds its reads again. A caller's reads are forgotten once its attempt
//! ends without [`NotYet`].
//!
//! The bytes are those of the first attempt that asked: a caller that
//! runs again on a changed view or variant must [`forget`] first (the
//! window does, whenever either changes).
//!
//! Where the thread may wait (the desktop), `later` runs the code once and
//! every read waits, as without it.

use std::cell::RefCell;
use std::collections::HashMap;
use std::panic::Location;

use anyhow::Result;

use super::pending_read::{PendingRead, Shape, Source};
use super::Gpu;

/// A read inside [`later`] whose copy is still on its way back.
#[derive(Debug, thiserror::Error)]
#[error("a readback is on its way: run again on a later frame")]
pub struct NotYet;

enum Read {
    Pending(PendingRead),
    Done(Vec<u8>),
}

#[derive(Default)]
struct Reads {
    /// Inside a [`later`] run on a thread that may not wait.
    active: bool,
    /// The thread may not wait ([`never_wait_here`], or a web page).
    no_wait: bool,
    /// The line that called the run under way.
    caller: Option<&'static Location<'static>>,
    /// How many reads this run made so far.
    order: usize,
    reads: HashMap<(&'static Location<'static>, usize, Shape), Read>,
}

thread_local! {
    static READS: RefCell<Reads> = RefCell::new(Reads {
        no_wait: cfg!(target_arch = "wasm32"),
        ..Default::default()
    });
}

/// Runs `f`, whose texture reads may not wait: `Some` of what it returned,
/// or `None` while a read is on its way (run `f` again on a later frame).
/// Where the thread may wait, `f` runs once, its reads waiting.
#[track_caller]
pub fn later<T>(f: impl FnOnce() -> Result<T>) -> Result<Option<T>> {
    let caller = Location::caller();
    let no_wait = READS.with(|r| r.borrow().no_wait);
    if !no_wait {
        return f().map(Some);
    }
    READS.with(|r| {
        let mut r = r.borrow_mut();
        r.active = true;
        r.caller = Some(caller);
        r.order = 0;
    });
    let result = f();
    READS.with(|r| r.borrow_mut().active = false);
    match result {
        Err(e) if e.chain().any(|c| c.is::<NotYet>()) => Ok(None),
        // Done: this caller's reads are forgotten (another's, still on
        // their way, are kept).
        done => {
            READS.with(|r| r.borrow_mut().reads.retain(|(c, _, _), _| *c != caller));
            done.map(Some)
        }
    }
}

/// Whether a run's reads are on their way back (or came back, and the run
/// has not yet been called again to take them): the window then draws its
/// next frames without a pause, and its `--capture` waits.
pub fn waiting() -> bool {
    READS.with(|r| !r.borrow().reads.is_empty())
}

/// Forgets every read on its way or done (the view or the variant changed).
pub fn forget() {
    READS.with(|r| r.borrow_mut().reads.clear());
}

/// Makes this thread's reads behave as a web page's (never wait): for
/// the tests, which check the page's path on the desktop.
pub fn never_wait_here() {
    READS.with(|r| r.borrow_mut().no_wait = true);
}

/// The source's bytes for [`super::readback::read_texture`] and
/// [`super::readback::read_buffer_copy`] on a thread that may not wait: `None` where it may (read as usual), else the
/// bytes of this read's copy, or [`NotYet`].
pub(super) fn read(gpu: &Gpu, source: &Source) -> Option<Result<Vec<u8>>> {
    READS.with(|r| {
        let mut r = r.borrow_mut();
        if !r.no_wait {
            return None;
        }
        if !r.active {
            // Outside a run a page cannot read at all; the desktop's
            // page-like window (its tests) still waits, for its capture.
            return match cfg!(target_arch = "wasm32") {
                true => Some(Err(anyhow::anyhow!(
                    "readback: a web page cannot wait for the GPU (read it inside read_later::later)"
                ))),
                false => None,
            };
        }
        let n = r.order;
        r.order += 1;
        let caller = r.caller.expect("set with active");
        let key = (caller, n, source.shape());
        #[cfg(not(target_arch = "wasm32"))]
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        let read = r.reads.entry(key).or_insert_with(|| {
            let pending = source.start(gpu);
            pending.map();
            Read::Pending(pending)
        });
        if let Read::Pending(pending) = read {
            match pending.take() {
                Some(Ok(bytes)) => *read = Read::Done(bytes),
                Some(Err(e)) => return Some(Err(e)),
                None => return Some(Err(NotYet.into())),
            }
        }
        match read {
            Read::Done(bytes) => Some(Ok(bytes.clone())),
            Read::Pending(_) => Some(Err(NotYet.into())),
        }
    })
}
