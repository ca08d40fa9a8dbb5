//! A headless Chromium driven through its DevTools protocol over a pipe
//! (`--remote-debugging-pipe`: JSON messages ended by NUL on file descriptors 3 and 4, set up
//! by `sh`), with one page attached: open a file at a viewport size, evaluate scripts, dispatch
//! input, take screenshots; script errors are collected. No crate beyond serde_json and
//! base64 (the screenshots' encoding), nothing to download: the browser is Debian's
//! `chromium`. Used by `report_in_browser.rs`.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use base64::Engine as _;
use serde_json::{Value, json};

/// How long one protocol call may take before the test fails instead of hanging.
const CALL_TIMEOUT: Duration = Duration::from_secs(60);

/// A headless Chromium driven over its DevTools pipe, with one page (a session) attached.
pub struct Chromium {
    child: Child,
    input: ChildStdin,
    messages: Receiver<Value>,
    next: u64,
    session: String,
    /// Script errors reported by the page (`Runtime.exceptionThrown`, console errors).
    pub errors: Vec<String>,
    /// The protocol events seen and not yet waited for, by method.
    events: Vec<Value>,
    _profile: tempfile::TempDir,
}

impl Chromium {
    /// The browser's program, if one is installed.
    pub fn program() -> Option<PathBuf> {
        let path = std::env::var_os("PATH")?;
        ["chromium", "chromium-browser", "google-chrome"]
            .iter()
            .flat_map(|name| std::env::split_paths(&path).map(move |dir| dir.join(name)))
            .find(|p| p.is_file())
    }

    /// Starts the browser with a fresh profile and attaches to a blank page.
    pub fn start(program: &Path) -> Result<Chromium, String> {
        let profile = tempfile::tempdir().map_err(|e| e.to_string())?;
        let mut child = Command::new("sh")
            .arg("-c")
            // The pipe: Chromium reads commands on fd 3 and writes answers on fd 4.
            .arg(r#"exec "$0" "$@" 3<&0 4>&1 0</dev/null 1>/dev/null"#)
            .arg(program)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--hide-scrollbars",
                "--force-device-scale-factor=1",
                "--remote-debugging-pipe",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg("about:blank")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| format!("cannot run {}: {e}", program.display()))?;
        let input = child.stdin.take().expect("piped");
        let output = child.stdout.take().expect("piped");
        let (send, messages) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(output);
            let mut buffer = Vec::new();
            while let Ok(n) = reader.read_until(0, &mut buffer) {
                if n == 0 {
                    break;
                }
                buffer.pop_if(|b| *b == 0);
                if let Ok(message) = serde_json::from_slice(&buffer)
                    && send.send(message).is_err()
                {
                    break;
                }
                buffer.clear();
            }
        });
        let mut browser = Chromium {
            child,
            input,
            messages,
            next: 0,
            session: String::new(),
            errors: Vec::new(),
            events: Vec::new(),
            _profile: profile,
        };
        let target = browser.call_browser("Target.createTarget", json!({"url": "about:blank"}))?;
        let attached = browser.call_browser(
            "Target.attachToTarget",
            json!({"targetId": target["targetId"], "flatten": true}),
        )?;
        browser.session = attached["sessionId"]
            .as_str()
            .ok_or("no session")?
            .to_owned();
        browser.call("Page.enable", json!({}))?;
        browser.call("Runtime.enable", json!({}))?;
        Ok(browser)
    }

    fn send(&mut self, mut message: Value) -> Result<u64, String> {
        self.next += 1;
        message["id"] = json!(self.next);
        let mut bytes = serde_json::to_vec(&message).map_err(|e| e.to_string())?;
        bytes.push(0);
        self.input
            .write_all(&bytes)
            .and_then(|()| self.input.flush())
            .map_err(|e| format!("the browser's pipe closed: {e}"))?;
        Ok(self.next)
    }

    /// The next message, or an error after [`CALL_TIMEOUT`]; events are kept, script errors
    /// noted.
    fn receive(&mut self) -> Result<Value, String> {
        match self.messages.recv_timeout(CALL_TIMEOUT) {
            Ok(message) => {
                match message["method"].as_str() {
                    Some("Runtime.exceptionThrown") => self.errors.push(
                        message["params"]["exceptionDetails"]["exception"]["description"]
                            .as_str()
                            .unwrap_or("an exception")
                            .to_owned(),
                    ),
                    Some("Runtime.consoleAPICalled")
                        if message["params"]["type"] == "error"
                            || message["params"]["type"] == "assert" =>
                    {
                        self.errors
                            .push(format!("console error: {}", message["params"]["args"]));
                    }
                    Some(_) => self.events.push(message.clone()),
                    None => {}
                }
                Ok(message)
            }
            Err(RecvTimeoutError::Timeout) => Err("the browser did not answer in time".into()),
            Err(RecvTimeoutError::Disconnected) => Err("the browser exited".into()),
        }
    }

    fn answer(&mut self, id: u64) -> Result<Value, String> {
        loop {
            let message = self.receive()?;
            if message["id"] == json!(id) {
                if let Some(error) = message.get("error") {
                    return Err(format!("protocol error: {error}"));
                }
                return Ok(message["result"].clone());
            }
        }
    }

    /// Calls a method of the browser itself.
    pub fn call_browser(&mut self, method: &str, params: Value) -> Result<Value, String> {
        let id = self.send(json!({"method": method, "params": params}))?;
        self.answer(id)
    }

    /// Calls a method of the page.
    pub fn call(&mut self, method: &str, params: Value) -> Result<Value, String> {
        let id = self.send(json!({"method": method, "params": params,
                                  "sessionId": self.session}))?;
        self.answer(id)
    }

    /// Waits for the page's event `method` (one seen before counts).
    pub fn wait_for(&mut self, method: &str) -> Result<(), String> {
        loop {
            if let Some(k) = self.events.iter().position(|e| e["method"] == method) {
                self.events.drain(..=k);
                return Ok(());
            }
            self.receive()?;
        }
    }

    /// Opens `url` at the given viewport and waits until it has loaded.
    pub fn open(&mut self, url: &str, (width, height): (u32, u32)) -> Result<(), String> {
        self.call(
            "Emulation.setDeviceMetricsOverride",
            json!({"width": width, "height": height, "deviceScaleFactor": 1, "mobile": false}),
        )?;
        self.events.clear();
        self.call("Page.navigate", json!({"url": url}))?;
        self.wait_for("Page.loadEventFired")
    }

    /// Evaluates `expression` in the page (awaiting a promise) and returns its value.
    pub fn eval(&mut self, expression: &str) -> Result<Value, String> {
        let result = self.call(
            "Runtime.evaluate",
            json!({"expression": expression, "returnByValue": true, "awaitPromise": true}),
        )?;
        if let Some(details) = result.get("exceptionDetails") {
            return Err(format!("script failed: {details}"));
        }
        Ok(result["result"]["value"].clone())
    }

    /// The RGBA pixels of a `size`-px square of the viewport centred on `at`.
    pub fn pixels(&mut self, at: [f64; 2], size: f64) -> Result<(u32, u32, Vec<u8>), String> {
        let shot = self.call(
            "Page.captureScreenshot",
            json!({"format": "png", "clip": {"x": at[0] - size / 2.0, "y": at[1] - size / 2.0,
                   "width": size, "height": size, "scale": 1}}),
        )?;
        let png = base64::engine::general_purpose::STANDARD
            .decode(shot["data"].as_str().ok_or("no screenshot")?)
            .map_err(|e| e.to_string())?;
        let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).map_err(|e| e.to_string())?;
        Ok((pixmap.width(), pixmap.height(), pixmap.data().to_vec()))
    }
}

impl Drop for Chromium {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
