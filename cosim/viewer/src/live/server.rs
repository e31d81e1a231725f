//! The live session's HTTP and WebSocket server on 127.0.0.1: `GET /?token=…` is the viewer
//! page, `GET /socket?token=…` (WebSocket) streams frames to the page and carries the operator's
//! commands back. Requests must name the served address as their `Host`, the handshake must come
//! from the page's own origin, and both carry the session's token ([`guard`](super::guard)). One
//! thread accepts connections and one serves each, at most [`MAX_CONNECTIONS`] at once; the
//! simulation thread only replaces each client's latest frame and reads commands, so a slow or
//! stalled browser never delays a step nor grows the session's memory.

use std::collections::VecDeque;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use serde::Deserialize;
use tungstenite::protocol::WebSocketConfig;
use tungstenite::{Message, WebSocket};

use super::guard::{header, query, Guard, Limiter};

/// Where the page's WebSocket connects.
pub const SOCKET_PATH: &str = "/socket";
/// Connections served at once; more get `503 Service Unavailable`.
pub const MAX_CONNECTIONS: usize = 8;
/// Commands per second one client may send (and at once); more are refused.
pub const COMMANDS_PER_SECOND: f64 = 20.0;
/// Largest message a client may send (bytes); a larger one ends its connection.
pub const MAX_MESSAGE: usize = 4096;
/// How long a client's socket may refuse a frame before the client is disconnected.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// How long a connection's thread waits for a command before sending queued frames again.
const POLL: Duration = Duration::from_millis(5);
/// Longest request head read before the connection is dropped.
const MAX_HEAD: usize = 16 * 1024;
/// How long a request head may take to arrive.
const HEAD_TIMEOUT: Duration = Duration::from_secs(5);
/// Replies and notices kept for a client that does not read (the oldest go first).
const MAX_PENDING: usize = 32;

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

/// A command and the client that sent it (to answer that client only).
pub struct Request {
    /// What the page asked for.
    pub command: Command,
    /// The page that sent it.
    pub client: Arc<Client>,
}

/// What waits to be sent to one connected page: its latest frame (a newer one replaces it) and,
/// in order, the notices and replies meant for it, both bounded.
#[derive(Debug, Default)]
pub struct Client {
    latest: Mutex<Option<Arc<str>>>,
    pending: Mutex<VecDeque<Arc<str>>>,
    gone: AtomicBool,
}

impl Client {
    /// Queues `message` for this client only.
    pub fn reply(&self, message: &str) {
        self.push(Arc::from(message));
    }

    fn push(&self, message: Arc<str>) {
        let mut pending = self.pending.lock().unwrap_or_else(PoisonError::into_inner);
        if pending.len() == MAX_PENDING {
            pending.pop_front();
        }
        pending.push_back(message);
    }

    /// The messages to send now: the pending ones, then the latest frame.
    fn take(&self) -> Vec<Arc<str>> {
        let mut messages: Vec<Arc<str>> =
            self.pending.lock().unwrap_or_else(PoisonError::into_inner).drain(..).collect();
        messages.extend(self.latest.lock().unwrap_or_else(PoisonError::into_inner).take());
        messages
    }
}

/// `{"refused": why}`: the reply to a command that changed nothing.
pub fn refusal(why: &str) -> String {
    serde_json::json!({ "refused": why }).to_string()
}

type Clients = Arc<Mutex<Vec<Arc<Client>>>>;

/// What every connection's thread shares.
struct Shared {
    page: String,
    guard: Guard,
    clients: Clients,
    commands: Sender<Request>,
}

/// A running server.
pub struct Server {
    /// The address it listens on.
    pub address: SocketAddr,
    /// The pages' commands, as they arrive.
    pub commands: Receiver<Request>,
    clients: Clients,
}

impl Server {
    /// Listens on 127.0.0.1:`port` (0: any free port) and serves `page` at `/` to requests that
    /// carry `token`.
    pub fn start(port: u16, token: String, page: String) -> std::io::Result<Server> {
        let listener = TcpListener::bind(("127.0.0.1", port))?;
        let address = listener.local_addr()?;
        let (commands_in, commands) = mpsc::channel();
        let clients: Clients = Arc::default();
        let shared = Arc::new(Shared {
            page,
            guard: Guard::new(address, token),
            clients: Arc::clone(&clients),
            commands: commands_in,
        });
        std::thread::Builder::new().name("live-accept".into()).spawn(move || accept(&listener, &shared))?;
        Ok(Server { address, commands, clients })
    }

    /// Makes `message` every connected page's latest frame (pages that went away are forgotten).
    pub fn broadcast(&self, message: &str) {
        let message: Arc<str> = Arc::from(message);
        let mut clients = self.clients.lock().unwrap_or_else(PoisonError::into_inner);
        clients.retain(|client| !client.gone.load(Ordering::Relaxed));
        for client in clients.iter() {
            *client.latest.lock().unwrap_or_else(PoisonError::into_inner) = Some(Arc::clone(&message));
        }
    }

    /// Whether a page has its socket open.
    pub fn has_page(&self) -> bool {
        self.clients.lock().unwrap_or_else(PoisonError::into_inner).iter().any(|c| !c.gone.load(Ordering::Relaxed))
    }

    /// Queues `message` for every page in order, dropping the frames before it (a reset).
    pub fn announce(&self, message: &str) {
        let message: Arc<str> = Arc::from(message);
        for client in self.clients.lock().unwrap_or_else(PoisonError::into_inner).iter() {
            client.latest.lock().unwrap_or_else(PoisonError::into_inner).take();
            client.push(Arc::clone(&message));
        }
    }
}

/// One of the [`MAX_CONNECTIONS`], given back when its connection ends.
struct Slot(Arc<AtomicUsize>);

impl Slot {
    fn take(open: &Arc<AtomicUsize>) -> Option<Slot> {
        let taken = open.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < MAX_CONNECTIONS).then_some(n + 1));
        taken.ok().map(|_| Slot(Arc::clone(open)))
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Accepts connections for ever: each is served on a thread of its own while a slot is free,
/// turned away with 503 otherwise, and dropped (with a log line) when no thread can be started.
fn accept(listener: &TcpListener, shared: &Arc<Shared>) {
    let open = Arc::new(AtomicUsize::new(0));
    for stream in listener.incoming() {
        let stream = match stream {
            Ok(stream) => stream,
            Err(e) => {
                eprintln!("live: cannot accept a connection: {e}");
                std::thread::sleep(Duration::from_millis(100));
                continue;
            }
        };
        let Some(slot) = Slot::take(&open) else {
            turn_away(stream);
            continue;
        };
        let shared = Arc::clone(shared);
        let spawned = std::thread::Builder::new().name("live-connection".into()).spawn(move || {
            let _slot = slot;
            serve(stream, &shared);
        });
        if let Err(e) = spawned {
            eprintln!("live: cannot start a thread for a connection, dropped it: {e}");
        }
    }
}

/// Answers a connection past [`MAX_CONNECTIONS`] with 503.
fn turn_away(mut stream: TcpStream) {
    let peer = peer(&stream);
    eprintln!("live: turned away {peer}: {MAX_CONNECTIONS} connections are open already");
    // Read what has arrived of the request, so that closing does not reset the connection
    // before the reply is read.
    let _ = stream.set_read_timeout(Some(Duration::from_millis(100)));
    let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
    let mut head = Vec::new();
    let mut buffer = [0; 1024];
    while head.len() < MAX_HEAD && !head.windows(4).any(|w| w == b"\r\n\r\n") {
        match stream.read(&mut buffer) {
            Ok(n) if n > 0 => head.extend_from_slice(&buffer[..n]),
            _ => break,
        }
    }
    let body = format!("busy: at most {MAX_CONNECTIONS} connections at once; close another page and retry\n");
    let reply = reply_head("503 Service Unavailable", "text/plain; charset=utf-8", body.len()) + &body;
    let _ = stream.write_all(reply.as_bytes());
}

fn peer(stream: &TcpStream) -> String {
    stream.peer_addr().map_or_else(|_| "an unknown peer".to_string(), |a| a.to_string())
}

/// Serves one connection: the page, the socket, 403 or 404. Errors end the connection only.
fn serve(stream: TcpStream, shared: &Shared) {
    let Some(head) = peek_head(&stream) else { return };
    let first_line = head.lines().next().unwrap_or_default().to_string();
    let target = first_line.split_whitespace().nth(1).unwrap_or_default();
    let is_upgrade = header(&head, "upgrade").is_some_and(|u| u.eq_ignore_ascii_case("websocket"));
    let guard = &shared.guard;
    if let Err(why) = guard.check_host(header(&head, "host")) {
        return refuse(stream, &head, &why);
    }
    let token = query(target, "token");
    match target.split('?').next() {
        Some(SOCKET_PATH) if is_upgrade => {
            match guard.check_origin(header(&head, "origin")).and_then(|()| guard.check_token(token)) {
                Ok(()) => open_socket(stream, shared),
                Err(why) => refuse(stream, &head, &why),
            }
        }
        Some("/") => match guard.check_token(token) {
            Ok(()) => respond(stream, &head, "200 OK", "text/html; charset=utf-8", &shared.page),
            Err(why) => refuse(stream, &head, &why),
        },
        _ => respond(stream, &head, "404 Not Found", "text/plain", "not found\n"),
    }
}

/// Completes the WebSocket handshake (messages bounded by [`MAX_MESSAGE`]) and relays.
fn open_socket(stream: TcpStream, shared: &Shared) {
    let config = WebSocketConfig::default().max_message_size(Some(MAX_MESSAGE)).max_frame_size(Some(MAX_MESSAGE));
    let peer = peer(&stream);
    if let Ok(socket) = tungstenite::accept_with_config(stream, Some(config)) {
        relay(socket, shared, &peer);
    }
}

/// 403 with the reason, and a log line naming the peer.
fn refuse(stream: TcpStream, head: &str, why: &str) {
    eprintln!("live: refused {}: {why}", peer(&stream));
    respond(stream, head, "403 Forbidden", "text/plain; charset=utf-8", &format!("forbidden: {why}\n"));
}

/// The request head (up to the blank line), peeked so that the WebSocket handshake can still
/// read it.
fn peek_head(stream: &TcpStream) -> Option<String> {
    stream.set_read_timeout(Some(Duration::from_millis(500))).ok()?;
    let deadline = Instant::now() + HEAD_TIMEOUT;
    let mut buffer = vec![0; MAX_HEAD];
    while Instant::now() < deadline {
        let seen = match stream.peek(&mut buffer) {
            Ok(seen) => seen,
            Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => continue,
            Err(_) => return None,
        };
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

fn reply_head(status: &str, content_type: &str, length: usize) -> String {
    format!(
        "HTTP/1.1 {status}\r\nContent-Type: {content_type}\r\nContent-Length: {length}\r\nCache-Control: no-store\r\n\
         Connection: close\r\n\r\n"
    )
}

fn respond(mut stream: TcpStream, head: &str, status: &str, content_type: &str, body: &str) {
    // The head was only peeked: consume it before answering.
    let mut consumed = vec![0; head.len()];
    if stream.read_exact(&mut consumed).is_err() {
        return;
    }
    let reply = reply_head(status, content_type, body.len()) + body;
    let _ = stream.write_all(reply.as_bytes());
}

/// Marks its client gone when the connection ends, so that the next broadcast forgets it.
struct Leaving<'a>(&'a Client);

impl Drop for Leaving<'_> {
    fn drop(&mut self) {
        self.0.gone.store(true, Ordering::Relaxed);
    }
}

/// Sends queued messages to the page and passes its commands on, until either side goes away
/// or the page stops reading for [`WRITE_TIMEOUT`].
fn relay(mut socket: WebSocket<TcpStream>, shared: &Shared, peer: &str) {
    let client = Arc::new(Client::default());
    shared.clients.lock().unwrap_or_else(PoisonError::into_inner).push(Arc::clone(&client));
    let _leaving = Leaving(&client);
    let stream = socket.get_ref();
    if stream.set_read_timeout(Some(POLL)).is_err() || stream.set_write_timeout(Some(WRITE_TIMEOUT)).is_err() {
        return;
    }
    let mut limiter = Limiter::new(COMMANDS_PER_SECOND);
    loop {
        for message in client.take() {
            if let Err(e) = socket.write(Message::text(message.as_ref())) {
                return stalled(&e, peer);
            }
        }
        if let Err(e) = socket.flush() {
            return stalled(&e, peer);
        }
        match socket.read() {
            Ok(Message::Text(text)) if !limiter.allow() => {
                client
                    .reply(&refusal(&format!("{}: more than {COMMANDS_PER_SECOND} commands per second", short(&text))));
            }
            Ok(Message::Text(text)) => match serde_json::from_str(text.as_str()) {
                Ok(command) => {
                    if shared.commands.send(Request { command, client: Arc::clone(&client) }).is_err() {
                        return;
                    }
                }
                Err(e) => client.reply(&refusal(&format!("{}: not a command ({e})", short(&text)))),
            },
            Ok(Message::Close(_)) => return,
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
            Err(tungstenite::Error::Capacity(e)) => {
                return eprintln!("live: disconnected {peer}: {e} (at most {MAX_MESSAGE} bytes per message)");
            }
            Err(_) => return,
        }
    }
}

/// A log line when a page stopped reading its frames.
fn stalled(error: &tungstenite::Error, peer: &str) {
    if let tungstenite::Error::Io(e) = error {
        if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) {
            eprintln!("live: disconnected {peer}: it read no frame for {} s", WRITE_TIMEOUT.as_secs());
        }
    }
}

/// The start of a client's message, for a reply about it.
fn short(text: &str) -> String {
    let mut end = text.len().min(80);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    if end < text.len() {
        format!("{}…", &text[..end])
    } else {
        text.to_string()
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

    /// A request to `server` with these head lines; the whole reply.
    fn request(server: &Server, target: &str, headers: &str) -> String {
        let mut stream = TcpStream::connect(server.address).unwrap();
        stream.write_all(format!("GET {target} HTTP/1.1\r\n{headers}\r\n").as_bytes()).unwrap();
        let mut reply = String::new();
        stream.read_to_string(&mut reply).unwrap();
        reply
    }

    #[test]
    fn the_server_serves_the_page_with_the_token_to_its_own_host_only() {
        let server = Server::start(0, "t0k".into(), "<p>page</p>".into()).unwrap();
        let host = format!("Host: 127.0.0.1:{}\r\n", server.address.port());
        let page = request(&server, "/?token=t0k", &host);
        assert!(page.starts_with("HTTP/1.1 200 OK\r\n") && page.ends_with("\r\n\r\n<p>page</p>"), "{page}");
        let local = request(&server, "/?token=t0k", &format!("Host: localhost:{}\r\n", server.address.port()));
        assert!(local.starts_with("HTTP/1.1 200 OK\r\n"), "{local}");
        assert!(request(&server, "/favicon.ico", &host).starts_with("HTTP/1.1 404 Not Found\r\n"));
        let foreign = request(&server, "/?token=t0k", "Host: attacker.example\r\n");
        let expected = format!(
            "forbidden: Host 'attacker.example' is not 127.0.0.1:{0} or localhost:{0}\n",
            server.address.port()
        );
        assert!(foreign.starts_with("HTTP/1.1 403 Forbidden\r\n") && foreign.ends_with(&expected), "{foreign}");
        assert!(request(&server, "/", "").starts_with("HTTP/1.1 403 Forbidden\r\n"));
        let wrong = request(&server, "/?token=t0x", &host);
        assert!(wrong.ends_with("forbidden: wrong token: open the address the command printed\n"), "{wrong}");
        let none = request(&server, "/", &host);
        assert!(none.starts_with("HTTP/1.1 403 Forbidden\r\n") && none.contains("no token"), "{none}");
    }

    #[test]
    fn the_socket_needs_the_pages_origin_and_the_token() {
        let server = Server::start(0, "t0k".into(), String::new()).unwrap();
        let port = server.address.port();
        let upgrade = "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\n\
                       Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";
        let handshake = |target: &str, origin: &str| {
            let mut stream = TcpStream::connect(server.address).unwrap();
            write!(stream, "GET {target} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n{upgrade}{origin}\r\n").unwrap();
            let mut reply = vec![0; 4096];
            let n = stream.read(&mut reply).unwrap();
            let mut reply = String::from_utf8_lossy(&reply[..n]).into_owned();
            // A refusal closes the connection: read the rest of it (an accepted socket stays open).
            if !reply.starts_with("HTTP/1.1 101 ") {
                stream.read_to_string(&mut reply).unwrap();
            }
            reply
        };
        let ok = handshake("/socket?token=t0k", &format!("Origin: http://127.0.0.1:{port}\r\n"));
        assert!(ok.starts_with("HTTP/1.1 101 Switching Protocols\r\n"), "{ok}");
        let evil = handshake("/socket?token=t0k", "Origin: http://evil.example\r\n");
        assert!(
            evil.starts_with("HTTP/1.1 403 Forbidden\r\n") && evil.contains("Origin 'http://evil.example'"),
            "{evil}"
        );
        let missing = handshake("/socket?token=t0k", "");
        assert!(missing.ends_with("forbidden: no Origin header on the WebSocket handshake\n"), "{missing}");
        let tokenless = handshake("/socket", &format!("Origin: http://localhost:{port}\r\n"));
        assert!(tokenless.starts_with("HTTP/1.1 403 Forbidden\r\n") && tokenless.contains("no token"), "{tokenless}");
    }

    #[test]
    fn a_client_that_never_reads_keeps_one_frame_pending() {
        let client = Arc::new(Client::default());
        let clients: Clients = Arc::new(Mutex::new(vec![Arc::clone(&client)]));
        let server = Server { address: SocketAddr::from(([127, 0, 0, 1], 0)), commands: mpsc::channel().1, clients };
        for i in 0..10_000 {
            server.broadcast(&format!("frame {i}"));
        }
        for i in 0..100 {
            server.announce(&format!("notice {i}"));
        }
        server.broadcast("frame last");
        let pending: Vec<String> = client.take().iter().map(|m| m.to_string()).collect();
        assert_eq!(pending.len(), MAX_PENDING + 1);
        assert_eq!((pending[0].as_str(), pending[MAX_PENDING].as_str()), ("notice 68", "frame last"));
        assert!(client.take().is_empty());
    }

    #[test]
    fn connections_past_the_limit_get_503_until_one_closes() {
        let server = Server::start(0, "t0k".into(), "<p>page</p>".into()).unwrap();
        let open: Vec<TcpStream> = (0..MAX_CONNECTIONS).map(|_| TcpStream::connect(server.address).unwrap()).collect();
        std::thread::sleep(Duration::from_millis(200));
        let busy = request(&server, "/?token=t0k", &format!("Host: 127.0.0.1:{}\r\n", server.address.port()));
        assert!(busy.starts_with("HTTP/1.1 503 Service Unavailable\r\n"), "{busy}");
        assert!(busy.ends_with("busy: at most 8 connections at once; close another page and retry\n"), "{busy}");
        drop(open);
        std::thread::sleep(Duration::from_millis(200));
        let served = request(&server, "/?token=t0k", &format!("Host: 127.0.0.1:{}\r\n", server.address.port()));
        assert!(served.starts_with("HTTP/1.1 200 OK\r\n"), "{served}");
    }
}
