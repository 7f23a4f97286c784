//! A small WebDriver client for the browser test: chromedriver on a local port, spoken to in
//! plain HTTP/1.1 over a TCP stream (one request per connection), JSON bodies. No driver
//! crate: the ones there are pull in an async runtime, and the project cares about its cold
//! build time.

use serde_json::{json, Value};
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// How long chromedriver may take to answer its first status request.
const STARTUP: Duration = Duration::from_secs(20);
/// Longest wait for one answer (a page load included).
const ANSWER: Duration = Duration::from_secs(60);

/// The browser and its driver, where Debian's packages `chromium` and `chromium-driver` put
/// them (or `CHROMIUM` and `CHROMEDRIVER`).
pub fn binaries() -> Option<(PathBuf, PathBuf)> {
    let find = |var: &str, name: &str| -> Option<PathBuf> {
        if let Ok(p) = std::env::var(var) {
            return Some(PathBuf::from(p)).filter(|p| p.exists());
        }
        let path = std::env::var_os("PATH")?;
        std::env::split_paths(&path)
            .map(|d| d.join(name))
            .find(|p| p.exists())
    };
    Some((
        find("CHROMIUM", "chromium")?,
        find("CHROMEDRIVER", "chromedriver")?,
    ))
}

/// A chromedriver process with one headless browser session; both end when dropped.
pub struct Browser {
    driver: Child,
    port: u16,
    session: String,
}

impl Browser {
    /// Starts chromedriver and a headless Chromium whose window is `width` × `height`.
    pub fn start(chromium: &Path, chromedriver: &Path, width: u32, height: u32) -> Browser {
        // A port the system just handed out, free again once the listener is dropped.
        let port = TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free local port")
            .port();
        let driver = Command::new(chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        let mut browser = Browser {
            driver,
            port,
            session: String::new(),
        };
        let start = Instant::now();
        while browser.request("GET", "/status", None).is_err() {
            assert!(start.elapsed() < STARTUP, "chromedriver does not answer");
            std::thread::sleep(Duration::from_millis(50));
        }
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": chromium,
                "args": ["--headless=new", "--no-sandbox", "--disable-gpu",
                         "--disable-dev-shm-usage", "--hide-scrollbars",
                         format!("--window-size={width},{height}")],
            },
            "goog:loggingPrefs": {"browser": "ALL"},
        }}});
        let answer = browser
            .request("POST", "/session", Some(&caps))
            .expect("a browser session");
        browser.session = answer["sessionId"]
            .as_str()
            .unwrap_or_else(|| panic!("no session: {answer}"))
            .to_owned();
        browser
    }

    /// One command of the session, e.g. `("POST", "url", {"url": ...})`; its `value`.
    pub fn command(&self, method: &str, path: &str, body: Option<&Value>) -> Value {
        let path = format!("/session/{}/{path}", self.session);
        match self.request(method, &path, body) {
            Ok(v) => v,
            Err(e) => panic!("{method} {path}: {e}"),
        }
    }

    /// Resizes the window so that the page's viewport is `width` × `height` (the window's
    /// frame, even headless, takes some of the window); the viewport's size then.
    pub fn viewport(&self, width: u32, height: u32) -> [f64; 2] {
        let read = || -> [f64; 2] {
            let v = self.run("return [window.innerWidth, window.innerHeight];", json!([]));
            serde_json::from_value(v).expect("the viewport's size")
        };
        // A resize may land after the command returns (a loaded machine): the size once two
        // reads 50 ms apart agree.
        let inner = || -> [f64; 2] {
            let mut last = read();
            for _ in 0..40 {
                std::thread::sleep(std::time::Duration::from_millis(50));
                let now = read();
                if now == last {
                    break;
                }
                last = now;
            }
            last
        };
        let (mut w, mut h) = (f64::from(width), f64::from(height));
        for _ in 0..5 {
            self.command(
                "POST",
                "window/rect",
                Some(&json!({"width": w, "height": h})),
            );
            let [iw, ih] = inner();
            if iw == f64::from(width) && ih == f64::from(height) {
                break;
            }
            (w, h) = (w + f64::from(width) - iw, h + f64::from(height) - ih);
        }
        inner()
    }

    /// Opens a page.
    pub fn open(&self, url: &str) {
        self.command("POST", "url", Some(&json!({ "url": url })));
    }

    /// Runs `script` (a function body) in the page with `args`; its return value.
    pub fn run(&self, script: &str, args: Value) -> Value {
        self.command(
            "POST",
            "execute/sync",
            Some(&json!({"script": script, "args": args})),
        )
    }

    /// Clicks the element that `css` selects, as a user would.
    pub fn click(&self, css: &str) {
        let found = self.command(
            "POST",
            "element",
            Some(&json!({"using": "css selector", "value": css})),
        );
        let id = found
            .as_object()
            .and_then(|o| o.values().next())
            .and_then(Value::as_str)
            .unwrap_or_else(|| panic!("no element {css}: {found}"))
            .to_owned();
        self.command("POST", &format!("element/{id}/click"), Some(&json!({})));
    }

    /// What the page logged to its console since the last call.
    pub fn console(&self) -> Vec<Value> {
        let logs = self.command("POST", "se/log", Some(&json!({"type": "browser"})));
        logs.as_array().cloned().unwrap_or_default()
    }

    /// The page as a PNG.
    pub fn screenshot(&self) -> Vec<u8> {
        let b64 = self.command("GET", "screenshot", None);
        base64_decode(b64.as_str().expect("a screenshot"))
    }

    fn request(&self, method: &str, path: &str, body: Option<&Value>) -> Result<Value, String> {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).map_err(|e| e.to_string())?;
        stream
            .set_read_timeout(Some(ANSWER))
            .map_err(|e| e.to_string())?;
        let body = body.map(Value::to_string).unwrap_or_default();
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
            self.port,
            body.len()
        );
        stream
            .write_all(head.as_bytes())
            .and_then(|_| stream.write_all(body.as_bytes()))
            .map_err(|e| e.to_string())?;
        // chromedriver keeps the connection open whatever the request says: read the header,
        // then as many bytes as it announces (or chunks up to the last).
        let mut raw = Vec::new();
        let mut buf = [0u8; 16384];
        let split = loop {
            if let Some(k) = raw.windows(4).position(|w| w == b"\r\n\r\n") {
                break k;
            }
            let n = stream.read(&mut buf).map_err(|e| e.to_string())?;
            if n == 0 {
                return Err("connection closed before the header".into());
            }
            raw.extend_from_slice(&buf[..n]);
        };
        let headers = String::from_utf8_lossy(&raw[..split]).to_ascii_lowercase();
        let mut content = raw[split + 4..].to_vec();
        let length = headers.lines().find_map(|l| {
            l.strip_prefix("content-length:")
                .and_then(|v| v.trim().parse::<usize>().ok())
        });
        let chunked = headers.contains("transfer-encoding: chunked");
        loop {
            let complete = match length {
                Some(n) => content.len() >= n,
                None if chunked => content.ends_with(b"0\r\n\r\n"),
                None => false,
            };
            if complete {
                break;
            }
            let n = stream.read(&mut buf).map_err(|e| e.to_string())?;
            if n == 0 {
                break;
            }
            content.extend_from_slice(&buf[..n]);
        }
        if chunked {
            content = unchunk(&content)?;
        }
        let v: Value = serde_json::from_slice(&content).map_err(|e| e.to_string())?;
        let status_ok = headers.starts_with("http/1.1 2");
        if !status_ok {
            return Err(format!("{}", v["value"]));
        }
        Ok(v["value"].clone())
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let path = format!("/session/{}", self.session);
            let _ = self.request("DELETE", &path, None);
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

fn unchunk(mut data: &[u8]) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    loop {
        let line = data
            .windows(2)
            .position(|w| w == b"\r\n")
            .ok_or("bad chunk")?;
        let size = usize::from_str_radix(String::from_utf8_lossy(&data[..line]).trim(), 16)
            .map_err(|e| e.to_string())?;
        if size == 0 {
            return Ok(out);
        }
        let start = line + 2;
        out.extend_from_slice(data.get(start..start + size).ok_or("short chunk")?);
        data = data.get(start + size + 2..).ok_or("short chunk")?;
    }
}

fn base64_decode(s: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let digits: Vec<u8> = s
        .bytes()
        .filter(|&c| c != b'=' && c != b'\n')
        .map(value)
        .collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let mut n = 0u32;
        for (k, &d) in chunk.iter().enumerate() {
            n |= u32::from(d) << (18 - 6 * k);
        }
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

#[test]
fn base64_decodes_what_it_should() {
    assert_eq!(base64_decode("TWFu"), b"Man");
    assert_eq!(base64_decode("TWE="), b"Ma");
    assert_eq!(base64_decode("TQ=="), b"M");
}
