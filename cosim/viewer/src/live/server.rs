//! The live session's HTTP and WebSocket server on 127.0.0.1: `GET /` is the viewer page,
//! `GET /socket` (WebSocket) streams frames to the page and carries the operator's commands
//! back. One thread accepts connections and one serves each; the simulation thread only
//! queues messages and reads commands, so a slow browser never delays a step.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use serde::Deserialize;
use tungstenite::{Message, WebSocket};

/// Where the page's WebSocket connects.
pub const SOCKET_PATH: &str = "/socket";
/// How long a connection's thread waits for a command before sending queued frames again.
const POLL: Duration = Duration::from_millis(5);
/// Longest request head read before the connection is dropped.
const MAX_HEAD: usize = 16 * 1024;

/// An operator's command from the page.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "command", rename_all = "lowercase")]
pub enum Command {
    /// Move the load set-point by `delta` (m, W = NED).
    Move {
        delta: [f64; 3],
    },
    /// Switch world-frame compensation on or off.
    Compensation {
        on: bool,
    },
    Pause,
    Resume,
    /// Start the run again from its initial state.
    Reset,
}

type Clients = Arc<Mutex<Vec<Sender<Arc<str>>>>>;

/// A running server.
pub struct Server {
    pub address: SocketAddr,
    pub commands: Receiver<Command>,
    clients: Clients,
}

impl Server {
    /// Listens on 127.0.0.1:`port` (0: any free port) and serves `page` at `/`.
    pub fn start(port: u16, page: String) -> std::io::Result<Server> {
        let listener = TcpListener::bind(("127.0.0.1", port))?;
        let address = listener.local_addr()?;
        let (commands_in, commands) = mpsc::channel();
        let clients: Clients = Arc::default();
        let (page, accepted) = (Arc::<str>::from(page), Arc::clone(&clients));
        std::thread::spawn(move || {
            for stream in listener.incoming().flatten() {
                let (page, clients, commands) = (Arc::clone(&page), Arc::clone(&accepted), commands_in.clone());
                std::thread::spawn(move || serve(stream, &page, &clients, &commands));
            }
        });
        Ok(Server { address, commands, clients })
    }

    /// Queues `message` for every connected page (pages that went away are forgotten).
    pub fn broadcast(&self, message: &str) {
        let message: Arc<str> = Arc::from(message);
        let mut clients = self.clients.lock().unwrap_or_else(PoisonError::into_inner);
        clients.retain(|client| client.send(Arc::clone(&message)).is_ok());
    }
}

/// Serves one connection: the page, the socket, or 404. Errors end the connection only.
fn serve(stream: TcpStream, page: &str, clients: &Clients, commands: &Sender<Command>) {
    let Some(head) = peek_head(&stream) else { return };
    let first_line = head.lines().next().unwrap_or_default().to_string();
    let is_upgrade = head.to_ascii_lowercase().contains("upgrade: websocket");
    match first_line.split_whitespace().nth(1) {
        Some(SOCKET_PATH) if is_upgrade => {
            if let Ok(socket) = tungstenite::accept(stream) {
                relay(socket, clients, commands);
            }
        }
        Some("/") => respond(stream, &head, "200 OK", "text/html; charset=utf-8", page),
        _ => respond(stream, &head, "404 Not Found", "text/plain", "not found\n"),
    }
}

/// The request head (up to the blank line), peeked so that the WebSocket handshake can still
/// read it.
fn peek_head(stream: &TcpStream) -> Option<String> {
    stream.set_read_timeout(Some(Duration::from_secs(5))).ok()?;
    let mut buffer = vec![0; MAX_HEAD];
    for _ in 0..100 {
        let seen = stream.peek(&mut buffer).ok()?;
        let text = String::from_utf8_lossy(&buffer[..seen]);
        if let Some(end) = text.find("\r\n\r\n") {
            return Some(text[..end + 4].to_string());
        }
        if seen == 0 || seen == MAX_HEAD {
            return None;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    None
}

fn respond(mut stream: TcpStream, head: &str, status: &str, content_type: &str, body: &str) {
    // The head was only peeked: consume it before answering.
    let mut consumed = vec![0; head.len()];
    if stream.read_exact(&mut consumed).is_err() {
        return;
    }
    let reply = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\
         Connection: close\r\n\r\n",
        body.len()
    );
    let _ = stream.write_all(reply.as_bytes()).and_then(|()| stream.write_all(body.as_bytes()));
}

/// Sends queued messages to the page and passes its commands on, until either side goes away.
fn relay(mut socket: WebSocket<TcpStream>, clients: &Clients, commands: &Sender<Command>) {
    let (queue, queued) = mpsc::channel();
    clients.lock().unwrap_or_else(PoisonError::into_inner).push(queue);
    if socket.get_ref().set_read_timeout(Some(POLL)).is_err() {
        return;
    }
    loop {
        for message in queued.try_iter() {
            if socket.write(Message::text(message.as_ref())).is_err() {
                return;
            }
        }
        if socket.flush().is_err() {
            return;
        }
        match socket.read() {
            Ok(Message::Text(text)) => {
                // A command that does not parse is ignored: the page is the only client.
                if let Ok(command) = serde_json::from_str(text.as_str()) {
                    if commands.send(command).is_err() {
                        return;
                    }
                }
            }
            Ok(Message::Close(_)) => return,
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
            Err(_) => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages the page (viewer/src/live.js) sends.
    #[test]
    fn the_pages_commands_parse() {
        let parse = |text: &str| serde_json::from_str::<Command>(text).unwrap();
        assert_eq!(parse(r#"{"command":"move","delta":[0.01,0,-0.01]}"#), Command::Move { delta: [0.01, 0.0, -0.01] });
        assert_eq!(parse(r#"{"command":"compensation","on":false}"#), Command::Compensation { on: false });
        assert_eq!(parse(r#"{"command":"pause"}"#), Command::Pause);
        assert_eq!(parse(r#"{"command":"resume"}"#), Command::Resume);
        assert_eq!(parse(r#"{"command":"reset"}"#), Command::Reset);
        assert!(serde_json::from_str::<Command>(r#"{"command":"move"}"#).is_err());
    }

    #[test]
    fn the_server_serves_the_page_and_nothing_else() {
        let server = Server::start(0, "<p>page</p>".into()).unwrap();
        let get = |path: &str| {
            let mut stream = TcpStream::connect(server.address).unwrap();
            write!(stream, "GET {path} HTTP/1.1\r\nHost: localhost\r\n\r\n").unwrap();
            let mut reply = String::new();
            stream.read_to_string(&mut reply).unwrap();
            reply
        };
        let page = get("/");
        assert!(page.starts_with("HTTP/1.1 200 OK\r\n") && page.ends_with("\r\n\r\n<p>page</p>"), "{page}");
        assert!(get("/favicon.ico").starts_with("HTTP/1.1 404 Not Found\r\n"));
    }
}
