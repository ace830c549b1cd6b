//! A display for the window where a program needs one and the machine may
//! have none: the window's tests and the book's window screenshots. On
//! Linux they run on a private Xvfb (so no window pops up on a desktop and
//! CI needs no display); elsewhere on the desktop.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use anyhow::{bail, Context, Result};

/// The display a window runs on; a private Xvfb ends when this drops.
pub struct Display {
    xvfb: Option<Child>,
    /// The X11 display's name (`:5`), when it is a private Xvfb.
    pub name: Option<String>,
}

impl Display {
    /// A private Xvfb on Linux (where `Xvfb` is installed), else the
    /// display the environment names; on Windows and macOS the desktop.
    pub fn open() -> Result<Display> {
        if cfg!(not(target_os = "linux")) {
            return Ok(Display {
                xvfb: None,
                name: None,
            });
        }
        match Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1920x1080x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
        {
            Ok(mut child) => {
                let out = child.stdout.take().context("Xvfb's stdout")?;
                let mut line = String::new();
                BufReader::new(out)
                    .read_line(&mut line)
                    .context("reading Xvfb's display number")?;
                let n = line.trim();
                if n.is_empty() || !n.chars().all(|c| c.is_ascii_digit()) {
                    let _ = child.kill();
                    bail!("Xvfb did not start (it printed {line:?} for its display)");
                }
                Ok(Display {
                    name: Some(format!(":{n}")),
                    xvfb: Some(child),
                })
            }
            Err(_) if std::env::var_os("DISPLAY").is_some_and(|d| !d.is_empty()) => Ok(Display {
                xvfb: None,
                name: None,
            }),
            Err(e) => bail!(
                "no display for the window and no Xvfb ({e}): install it (apt-get install -y xvfb) or set DISPLAY"
            ),
        }
    }

    /// Points `cmd` at this display.
    pub fn apply(&self, cmd: &mut Command) {
        if let Some(name) = &self.name {
            cmd.env("DISPLAY", name).env_remove("WAYLAND_DISPLAY");
        }
    }
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(c) = &mut self.xvfb {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}
