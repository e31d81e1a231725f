//! Opening files a user named (FMUs, system, scenario and input files) defensively.
//!
//! Only regular files are opened: a FIFO would block `open` until a writer appears and a device
//! such as `/dev/zero` never ends, so both are refused from their metadata before opening.
//! Whole-file reads stop at a size limit instead of exhausting memory.

use std::fs;
use std::io::{self, Read};
use std::path::Path;

/// Largest text file (system, scenario, model description) read into memory: 64 MiB.
pub const MAX_TEXT_FILE_BYTES: u64 = 64 << 20;

/// Largest table (input or results CSV) read into memory: 1 GiB.
pub const MAX_TABLE_FILE_BYTES: u64 = 1 << 30;

/// Opens `path` for reading if it is a regular file (symbolic links followed).
///
/// Anything else is an [`io::ErrorKind::InvalidInput`] error saying what the path is.
pub fn open_regular(path: &Path) -> io::Result<fs::File> {
    let kind = fs::metadata(path)?.file_type();
    if !kind.is_file() {
        return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("not a regular file but {}", describe(kind))));
    }
    fs::File::open(path)
}

/// Reads the regular file `path` whole, refusing files larger than `limit` bytes (checked while
/// reading, so a file that grows meanwhile is refused too).
pub fn read_regular(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    let file = open_regular(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("larger than the limit of {}", human_bytes(limit)),
        ));
    }
    Ok(bytes)
}

/// [`read_regular`] as UTF-8 text.
pub fn read_regular_text(path: &Path, limit: u64) -> io::Result<String> {
    String::from_utf8(read_regular(path, limit)?).map_err(|error| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not valid UTF-8 (byte {})", error.utf8_error().valid_up_to()),
        )
    })
}

/// A byte count for messages: exact below 1 KiB, else in KiB/MiB/GiB with one decimal.
pub fn human_bytes(bytes: u64) -> String {
    const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
    if bytes < 1024 {
        return format!("{bytes} bytes");
    }
    let mut value = bytes as f64 / 1024.0;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    format!("{value:.1} {}", UNITS[unit])
}

fn describe(kind: fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a directory"
    } else {
        "a special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_and_directories_are_refused_before_reading() {
        let dir = tempfile::tempdir().expect("tempdir");
        let error = read_regular(dir.path(), 10).unwrap_err();
        assert_eq!(error.to_string(), "not a regular file but a directory");
        #[cfg(unix)]
        {
            let error = read_regular(Path::new("/dev/zero"), 10).unwrap_err();
            assert_eq!(error.to_string(), "not a regular file but a device");
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = tempfile::tempdir().expect("tempdir");
        let fifo = dir.path().join("pipe.fmu");
        let status = std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
        assert!(status.success());
        // Opening a FIFO for reading blocks until a writer appears: this returning at all is the test.
        let error = open_regular(&fifo).unwrap_err();
        assert_eq!(error.to_string(), "not a regular file but a FIFO");
    }

    #[test]
    fn files_over_the_limit_are_refused() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("a.json");
        fs::write(&path, "0123456789").expect("write");
        assert_eq!(read_regular(&path, 10).expect("at the limit"), b"0123456789");
        let error = read_regular(&path, 9).unwrap_err();
        assert_eq!(error.to_string(), "larger than the limit of 9 bytes");
    }

    #[test]
    fn byte_counts_read_naturally() {
        assert_eq!(human_bytes(1023), "1023 bytes");
        assert_eq!(human_bytes(64 << 20), "64.0 MiB");
        assert_eq!(human_bytes(4_800_000_000), "4.5 GiB");
    }
}
