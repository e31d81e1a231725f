//! `crane-cosim live` as a browser and a stranger meet it: only the printed address (with its
//! token) from the page's own origin is served, commands out of bounds are refused to their
//! sender while the session runs on, and resets record at most a bounded number of files.
//!
//! Needs the packaged FMUs in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, ChildStderr, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;
use tungstenite::client::IntoClientRequest;
use tungstenite::{Message, WebSocket};

/// A running `crane-cosim live` on a free port, killed when dropped.
struct Live {
    child: Child,
    /// `127.0.0.1:PORT`.
    host: String,
    token: String,
}

impl Live {
    fn start(options: &[&str]) -> Live {
        Live::start_with("scenarios/demo_still_compensated.json", options)
    }

    /// A session of `scenario` (relative to the workspace root).
    fn start_with(scenario: &str, options: &[&str]) -> Live {
        Live::start_until(scenario, "600", options)
    }

    /// A session of `scenario` that ends at simulated time `stop_time`.
    fn start_until(scenario: &str, stop_time: &str, options: &[&str]) -> Live {
        let scenario = common::workspace_root().join(scenario);
        let mut child = common::crane_cosim_command()
            .arg("live")
            .arg(scenario)
            .args(["--port", "0", "--stop-time", stop_time])
            .args(options)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("crane-cosim runs");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
        // "serving http://127.0.0.1:PORT/?token=TOKEN (Ctrl-C ends the session)"
        let url = line.split_whitespace().nth(1).unwrap_or_else(|| panic!("no address in {line:?}"));
        let (host, token) = url.trim_start_matches("http://").split_once("/?token=").unwrap();
        assert_eq!(token.len(), 32, "{url}");
        Live { child, host: host.to_string(), token: token.to_string() }
    }

    /// The reply to a plain GET with these head lines.
    fn get(&self, target: &str, headers: &str) -> String {
        let mut stream = TcpStream::connect(&self.host).unwrap();
        stream.write_all(format!("GET {target} HTTP/1.1\r\n{headers}\r\n").as_bytes()).unwrap();
        let mut reply = String::new();
        stream.read_to_string(&mut reply).unwrap();
        reply
    }

    /// A WebSocket to `target` from `origin`, or the handshake's HTTP status.
    fn socket(&self, target: &str, origin: &str) -> Result<WebSocket<TcpStream>, u16> {
        let mut request = format!("ws://{}{target}", self.host).into_client_request().unwrap();
        request.headers_mut().insert("Origin", origin.parse().unwrap());
        let stream = TcpStream::connect(&self.host).unwrap();
        stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        match tungstenite::client(request, stream) {
            Ok((socket, _)) => Ok(socket),
            Err(tungstenite::HandshakeError::Failure(tungstenite::Error::Http(response))) => {
                Err(response.status().as_u16())
            }
            Err(e) => panic!("handshake: {e}"),
        }
    }

    /// The page's own socket.
    fn page_socket(&self) -> WebSocket<TcpStream> {
        self.socket(&format!("/socket?token={}", self.token), &format!("http://{}", self.host)).unwrap()
    }

    /// Whether the session ended on its own within `seconds`.
    fn ends_within(&mut self, seconds: u64) -> bool {
        let deadline = Instant::now() + Duration::from_secs(seconds);
        while Instant::now() < deadline {
            if self.child.try_wait().unwrap().is_some() {
                return true;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        false
    }

    /// Kills the session; its stderr.
    /// Ends the session as Ctrl-C does (SIGINT: the recording is closed and put in place) and
    /// returns what it wrote to stderr.
    fn stop(mut self) -> String {
        // SAFETY: sending a signal to our own child.
        assert_eq!(unsafe { libc::kill(self.child.id() as i32, libc::SIGINT) }, 0);
        let _ = self.child.wait();
        let mut err = String::new();
        let stderr: &mut ChildStderr = self.child.stderr.as_mut().unwrap();
        stderr.read_to_string(&mut err).unwrap();
        err
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn send(socket: &mut WebSocket<TcpStream>, command: &str) {
    socket.send(Message::text(command)).unwrap();
}

/// The next message that has `key`, within 20 s.
fn next_with(socket: &mut WebSocket<TcpStream>, key: &str) -> Value {
    let deadline = Instant::now() + Duration::from_secs(20);
    while Instant::now() < deadline {
        if let Message::Text(text) = socket.read().unwrap() {
            let message: Value = serde_json::from_str(text.as_str()).unwrap();
            if message.get(key).is_some() {
                return message;
            }
        }
    }
    panic!("no message with {key:?} within 20 s");
}

#[test]
fn the_session_starts_simulating_when_its_page_connects_or_at_once_with_no_wait() {
    const DEMO: &str = "scenarios/demo_still_compensated.json";
    // Half a simulated second is over well within 3 s; without a page, nothing has run.
    let mut live = Live::start_until(DEMO, "0.5", &[]);
    assert!(!live.ends_within(3), "the session ran without a page");
    let _page = live.page_socket();
    assert!(live.ends_within(30), "the session did not run once its page connected");
    let mut at_once = Live::start_until(DEMO, "0.5", &["--no-wait"]);
    assert!(at_once.ends_within(30), "--no-wait did not start the session at once");
}

#[test]
fn only_the_printed_address_from_the_pages_origin_is_served() {
    let live = Live::start(&[]);
    let host = format!("Host: {}\r\n", live.host);
    let page = live.get(&format!("/?token={}", live.token), &host);
    assert!(page.starts_with("HTTP/1.1 200 OK\r\n"), "{page}");
    assert!(page.contains(&format!("/socket?token={}", live.token)), "the page connects with the token");
    let port = live.host.trim_start_matches("127.0.0.1:");
    let foreign = live.get(&format!("/?token={}", live.token), "Host: attacker.example\r\n");
    assert!(foreign.starts_with("HTTP/1.1 403 Forbidden\r\n"), "{foreign}");
    assert!(
        foreign.ends_with(&format!("forbidden: Host 'attacker.example' is not 127.0.0.1:{port} or localhost:{port}\n")),
        "{foreign}"
    );
    let tokenless = live.get("/", &host);
    assert!(tokenless.ends_with("forbidden: no token: open the address the command printed (it ends with ?token=…)\n"));
    let wrong = live.get("/?token=0123456789abcdef0123456789abcdef", &host);
    assert!(wrong.ends_with("forbidden: wrong token: open the address the command printed\n"), "{wrong}");
    let socket = format!("/socket?token={}", live.token);
    assert_eq!(live.socket(&socket, "http://evil.example").err(), Some(403));
    assert_eq!(live.socket("/socket", &format!("http://{}", live.host)).err(), Some(403));
    assert_eq!(live.socket("/socket?token=x", &format!("http://localhost:{port}")).err(), Some(403));
    assert!(live.socket(&socket, &format!("http://localhost:{port}")).is_ok());
    let err = live.stop();
    assert!(err.contains("live: refused 127.0.0.1:"), "{err}");
    assert!(err.contains(": Origin 'http://evil.example' is not http://127.0.0.1:"), "{err}");
}

#[test]
fn moves_out_of_bounds_are_refused_to_the_sender_and_the_session_runs_on() {
    let live = Live::start(&[]);
    let mut socket = live.page_socket();
    let mut other = live.page_socket();
    let start = next_with(&mut socket, "frame");
    let setpoint = start["state"]["setpoint"].clone();
    send(&mut socket, r#"{"command":"move","delta":[0,0,-5]}"#);
    let refused = next_with(&mut socket, "refused");
    assert_eq!(refused["refused"], "move [0, 0, -5]: 5 m down is more than 0.1 m per move");
    for _ in 0..2 {
        send(&mut socket, r#"{"command":"move","delta":[1e308,1e308,1e308]}"#);
        let refused = next_with(&mut socket, "refused");
        assert_eq!(refused["refused"], "move [1e308, 1e308, 1e308]: 1e308 m north is more than 0.1 m per move");
    }
    // Nine moves up of 0.05 m shorten the 0.7 m cable to 0.25 m; 0.1 m more would leave 0.15 m.
    for _ in 0..9 {
        send(&mut socket, r#"{"command":"move","delta":[0,0,-0.05]}"#);
    }
    send(&mut socket, r#"{"command":"move","delta":[0,0,-0.1]}"#);
    let refused = next_with(&mut socket, "refused");
    assert_eq!(refused["refused"], "move [0, 0, -0.1]: cable length 0.250 m − 0.1 m = 0.150 m is outside 0.2…1.2 m");
    send(&mut socket, r#"{"command":"move","delta":[0.01,0,0]}"#);
    send(&mut socket, "{\"command\":\"fly\"}");
    let refused = next_with(&mut socket, "refused");
    assert!(refused["refused"].as_str().unwrap().starts_with("{\"command\":\"fly\"}: not a command ("), "{refused}");
    let later = next_with(&mut socket, "frame");
    let moved = &later["state"]["setpoint"];
    let expected = setpoint[0].as_f64().unwrap() + 0.01;
    assert!((moved[0].as_f64().unwrap() - expected).abs() < 1e-12, "{moved} after {setpoint}");
    assert!(later["frame"]["time"].as_f64() > start["frame"]["time"].as_f64());
    // The other page saw the frames, not the refusals.
    let deadline = Instant::now() + Duration::from_secs(2);
    while Instant::now() < deadline {
        if let Message::Text(text) = other.read().unwrap() {
            assert!(!text.as_str().contains("refused"), "{text}");
        }
    }
}

#[test]
fn resets_past_the_cap_record_nothing_more() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("session.csv");
    let live = Live::start(&["--record", record.to_str().unwrap()]);
    let mut socket = live.page_socket();
    for _ in 0..24 {
        send(&mut socket, r#"{"command":"reset"}"#);
        std::thread::sleep(Duration::from_millis(60));
    }
    let deadline = Instant::now() + Duration::from_secs(60);
    let state = loop {
        let message = next_with(&mut socket, "state");
        if message["state"].get("notice").is_some() || Instant::now() > deadline {
            break message["state"].clone();
        }
    };
    assert_eq!(state["recording"], Value::Null, "{state}");
    let last = dir.path().join("session-20.csv");
    let notice = format!(
        "recording stopped: 20 runs were recorded ({} … {}), the most per session",
        record.display(),
        last.display()
    );
    assert_eq!(state["notice"], notice.as_str());
    let err = live.stop();
    assert_eq!(err.matches("recording stopped").count(), 1, "{err}");
    assert_eq!(csv_files(dir.path()), 20);
}

#[test]
fn the_full_scale_crane_streams_its_cylinders_and_the_operator_switches_its_controllers_mode() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("session.csv");
    let live =
        Live::start_with("scenarios/full_scale_profile1_compensated.json", &["--record", record.to_str().unwrap()]);
    let page = live.get(&format!("/?token={}", live.token), &format!("Host: {}\r\n", live.host));
    assert!(page.contains(r#""mode":"live","title":"full_scale_profile1_compensated","scale":"full""#), "{page}");
    let mut socket = live.page_socket();
    let first = next_with(&mut socket, "frame");
    assert_eq!(first["frame"]["cylinders"].as_array().map(Vec::len), Some(6), "{first}");
    assert!(first["frame"].get("setpoint").is_none() && first["frame"].get("estimated_load").is_none());
    // The scenario starts the controller compensating (mode 2); it has no set-point to move.
    assert_eq!((&first["state"]["compensation"], &first["state"]["setpoint"]), (&Value::Bool(true), &Value::Null));
    send(&mut socket, r#"{"command":"move","delta":[0.01,0,0]}"#);
    let refused = next_with(&mut socket, "refused");
    assert!(refused["refused"]
        .as_str()
        .unwrap()
        .starts_with("no set-point to move: the full-scale crane's controller"));
    send(&mut socket, r#"{"command":"compensation","on":false}"#);
    let switched = loop {
        let message = next_with(&mut socket, "frame");
        if message["state"]["compensation"] == false {
            break message;
        }
    };
    // 2.5 s more at real time: the recorder writes its rows at least every second.
    let at = switched["frame"]["time"].as_f64().unwrap();
    while next_with(&mut socket, "frame")["frame"]["time"].as_f64().unwrap() < at + 2.5 {}
    live.stop();
    let (header, rows) = common::read_results(&record);
    let mode = header.iter().position(|h| h == "knuckle_boom_controller.mode").expect("the mode is recorded");
    let modes: Vec<f64> = rows.iter().map(|r| r[mode]).collect();
    assert_eq!((modes[0], *modes.last().unwrap()), (2.0, 1.0), "positioning after the switch");
    assert!(header.iter().any(|h| h == "knuckle_boom.joint.slew"), "the view's variables are recorded");
}

fn csv_files(dir: &Path) -> usize {
    std::fs::read_dir(dir).unwrap().filter(|e| e.as_ref().unwrap().path().extension() == Some("csv".as_ref())).count()
}
