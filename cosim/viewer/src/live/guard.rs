//! Who may use the live session: the request's `Host` must be the served address, the
//! WebSocket handshake's `Origin` the page's own, and both the page and the socket carry the
//! session's random token — so another site open in the same browser, or another local user who
//! does not hold the printed address, can neither read the session nor drive the crane.

use std::net::SocketAddr;
use std::time::Instant;

/// Random bytes of a session token (128 bits).
const TOKEN_BYTES: usize = 16;

/// The session's access token, hex.
pub fn new_token() -> std::io::Result<String> {
    let mut bytes = [0u8; TOKEN_BYTES];
    getrandom::fill(&mut bytes).map_err(std::io::Error::other)?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// What a request must carry to be served.
#[derive(Debug, Clone)]
pub struct Guard {
    /// `127.0.0.1:PORT` and `localhost:PORT`.
    hosts: [String; 2],
    token: String,
}

impl Guard {
    pub fn new(address: SocketAddr, token: String) -> Guard {
        let port = address.port();
        Guard { hosts: [format!("127.0.0.1:{port}"), format!("localhost:{port}")], token }
    }

    /// Why a request with this `Host` header is refused, if it is.
    pub fn check_host(&self, host: Option<&str>) -> Result<(), String> {
        match host {
            Some(host) if self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) => Ok(()),
            Some(host) => Err(format!("Host '{host}' is not {} or {}", self.hosts[0], self.hosts[1])),
            None => Err(format!("no Host header (expected {} or {})", self.hosts[0], self.hosts[1])),
        }
    }

    /// Why a WebSocket handshake with this `Origin` header is refused, if it is (browsers always
    /// send one, so a missing Origin is refused too).
    pub fn check_origin(&self, origin: Option<&str>) -> Result<(), String> {
        let allowed = |origin: &str| self.hosts.iter().any(|h| origin.eq_ignore_ascii_case(&format!("http://{h}")));
        match origin {
            Some(origin) if allowed(origin) => Ok(()),
            Some(origin) => {
                Err(format!("Origin '{origin}' is not http://{} or http://{}", self.hosts[0], self.hosts[1]))
            }
            None => Err("no Origin header on the WebSocket handshake".to_string()),
        }
    }

    /// Why a request whose query carries this `token` is refused, if it is. Compared in
    /// constant time, so the reply's timing says nothing about how much of a guess was right.
    pub fn check_token(&self, token: Option<&str>) -> Result<(), String> {
        match token {
            Some(token) if constant_time_eq(token.as_bytes(), self.token.as_bytes()) => Ok(()),
            Some(_) => Err("wrong token: open the address the command printed".to_string()),
            None => Err("no token: open the address the command printed (it ends with ?token=…)".to_string()),
        }
    }
}

fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |diff, (x, y)| diff | (x ^ y)) == 0
}

/// A header's value in a request head (case-insensitive name).
pub fn header<'h>(head: &'h str, name: &str) -> Option<&'h str> {
    head.lines().skip(1).find_map(|line| {
        let (key, value) = line.split_once(':')?;
        key.trim().eq_ignore_ascii_case(name).then(|| value.trim())
    })
}

/// A query parameter of a request target (`/path?key=value&…`).
pub fn query<'t>(target: &'t str, key: &str) -> Option<&'t str> {
    let (_, query) = target.split_once('?')?;
    query.split('&').find_map(|pair| pair.split_once('=').filter(|(k, _)| *k == key).map(|(_, v)| v))
}

/// A token bucket: `rate` commands per second, up to `rate` at once.
#[derive(Debug)]
pub struct Limiter {
    rate: f64,
    tokens: f64,
    last: Instant,
}

impl Limiter {
    pub fn new(rate: f64) -> Limiter {
        Limiter { rate, tokens: rate, last: Instant::now() }
    }

    /// True when one more command is allowed now.
    pub fn allow(&mut self) -> bool {
        self.allow_at(Instant::now())
    }

    fn allow_at(&mut self, now: Instant) -> bool {
        let elapsed = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now;
        self.tokens = (self.tokens + elapsed * self.rate).min(self.rate);
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn guard() -> Guard {
        Guard::new(SocketAddr::from(([127, 0, 0, 1], 8023)), "00ff".into())
    }

    #[test]
    fn only_the_served_address_is_a_host_and_an_origin() {
        let guard = guard();
        assert_eq!(guard.check_host(Some("127.0.0.1:8023")), Ok(()));
        assert_eq!(guard.check_host(Some("localhost:8023")), Ok(()));
        assert_eq!(
            guard.check_host(Some("attacker.example")),
            Err("Host 'attacker.example' is not 127.0.0.1:8023 or localhost:8023".into())
        );
        assert!(guard.check_host(Some("localhost:8024")).is_err());
        assert_eq!(guard.check_host(None), Err("no Host header (expected 127.0.0.1:8023 or localhost:8023)".into()));
        assert_eq!(guard.check_origin(Some("http://localhost:8023")), Ok(()));
        assert_eq!(
            guard.check_origin(Some("http://evil.example")),
            Err("Origin 'http://evil.example' is not http://127.0.0.1:8023 or http://localhost:8023".into())
        );
        assert_eq!(guard.check_origin(None), Err("no Origin header on the WebSocket handshake".into()));
    }

    #[test]
    fn the_token_must_match_exactly() {
        let guard = guard();
        assert_eq!(guard.check_token(Some("00ff")), Ok(()));
        assert!(guard.check_token(Some("00fe")).is_err());
        assert!(guard.check_token(Some("00ff0")).is_err());
        assert!(guard.check_token(None).is_err());
        assert_eq!(query("/socket?x=1&token=ab", "token"), Some("ab"));
        assert_eq!(query("/socket", "token"), None);
        let token = new_token().unwrap();
        assert_eq!(token.len(), 32);
        assert_ne!(token, new_token().unwrap());
    }

    #[test]
    fn the_limiter_allows_a_burst_then_the_rate() {
        let mut limiter = Limiter::new(20.0);
        let start = limiter.last;
        assert_eq!((0..25).filter(|_| limiter.allow_at(start)).count(), 20);
        assert!(limiter.allow_at(start + Duration::from_millis(50)));
        assert!(!limiter.allow_at(start + Duration::from_millis(50)));
    }
}
