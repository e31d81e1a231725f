//! `file:` URIs for `fmuResourceLocation`.

use std::path::Path;

/// Percent-encodes an absolute path as a `file:///...` URI, the way Python's
/// `pathlib.Path.as_uri()` does (what FMPy passes): every byte except
/// `A–Z a–z 0–9 - . _ ~ /` is written as `%XX`, so spaces and UTF-8 survive.
/// No trailing slash is added.
pub fn file_uri(path: &Path) -> String {
    let bytes = path_bytes(path);
    let mut uri = String::from("file://");
    if !bytes.starts_with(b"/") {
        uri.push('/');
    }
    for &byte in bytes.iter() {
        if byte.is_ascii_alphanumeric() || matches!(byte, b'-' | b'.' | b'_' | b'~' | b'/') {
            uri.push(char::from(byte));
        } else {
            uri.push_str(&format!("%{byte:02X}"));
        }
    }
    uri
}

#[cfg(unix)]
fn path_bytes(path: &Path) -> std::borrow::Cow<'_, [u8]> {
    use std::os::unix::ffi::OsStrExt;
    std::borrow::Cow::Borrowed(path.as_os_str().as_bytes())
}

#[cfg(not(unix))]
fn path_bytes(path: &Path) -> std::borrow::Cow<'_, [u8]> {
    std::borrow::Cow::Owned(path.to_string_lossy().replace('\\', "/").into_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodes_spaces_and_utf8() {
        assert_eq!(file_uri(Path::new("/a b/ü/resources")), "file:///a%20b/%C3%BC/resources");
        assert_eq!(file_uri(Path::new("/x/y-z_1.~")), "file:///x/y-z_1.~");
        assert_eq!(file_uri(Path::new("/p%q#r")), "file:///p%25q%23r");
    }
}
