//! The bytes of a serialized FMU state (`fmi2SerializeFMUstate`): a header that says which
//! format and which build wrote them, then the instance's `Core` in postcard's encoding.
//!
//! Layout, in this order:
//! 1. [`MAGIC`], 8 bytes: these are bytes of this exporter's state images at all.
//! 2. The format version, a little-endian `u16` ([`FORMAT_VERSION`]): fixed-width so that any
//!    later version of this reader can read it whatever follows.
//! 3. The [`Identity`] of the FMU that wrote the image: its `modelIdentifier` and the GUID of
//!    its model description (a hash of the description, see [`crate::xml`]), postcard strings.
//! 4. The payload (the instance's core), postcard-encoded, to the last byte (trailing bytes are
//!    refused).
//!
//! Everything is checked in that order and the first mismatch is the message: a host that
//! passes the image of another model, another build or an older format learns which, and no
//! byte of the core is decoded before the header has matched. postcard (not bincode 1, which
//! is unmaintained, RUSTSEC-2025-0141) writes `f64` as its 8 little-endian bytes, so a round
//! trip is bit for bit.

use serde::{de::DeserializeOwned, Serialize};

/// The first bytes of every image ("FMI2 Rust state").
pub const MAGIC: [u8; 8] = *b"FMI2RsSt";

/// The layout described in the module documentation. Version 0 was the bincode 1 image.
pub const FORMAT_VERSION: u16 = 1;

/// The tag that began the images of the bincode format (a little-endian `u64`; earlier builds
/// also marked live instances with it), recognised only to say why such an image is refused.
pub(crate) const BINCODE_TAG: [u8; 8] = 0x464d_4932_5253_0001u64.to_le_bytes();

/// Which FMU build an image belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Identity<'a> {
    pub model_identifier: &'a str,
    pub guid: &'a str,
}

/// The image of `core` (an instance's `Core`) as written by the FMU `identity`.
pub fn encode<T: Serialize>(identity: Identity, core: &T) -> Result<Vec<u8>, String> {
    postcard::to_extend(core, header(identity)?).map_err(|e| format!("cannot encode the state: {e}"))
}

/// The bytes before the core: magic, format version and identity.
pub(crate) fn header(identity: Identity) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::with_capacity(256);
    bytes.extend_from_slice(&MAGIC);
    bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    postcard::to_extend(&identity, bytes).map_err(|e| format!("cannot encode the header: {e}"))
}

/// The core in `bytes`, if they are an image of this format written by the FMU `ours`; else
/// what does not match, for the host's log.
pub fn decode<T: DeserializeOwned>(ours: Identity, bytes: &[u8]) -> Result<T, String> {
    let body = check_magic(bytes)?;
    let (version, body) = body.split_first_chunk::<2>().ok_or_else(|| truncated("the format version"))?;
    let version = u16::from_le_bytes(*version);
    if version != FORMAT_VERSION {
        return Err(format!("the image has format version {version}; this build reads version {FORMAT_VERSION}"));
    }
    let (theirs, body) = postcard::take_from_bytes::<Identity>(body).map_err(|_| truncated("the FMU's identity"))?;
    check_identity(ours, theirs)?;
    let (core, rest) = postcard::take_from_bytes::<T>(body)
        .map_err(|e| format!("the state in the image is truncated or corrupted ({e})"))?;
    if !rest.is_empty() {
        return Err(format!("the image has {} bytes after the state", rest.len()));
    }
    Ok(core)
}

/// The bytes after the magic, or why they are not an image of this exporter.
fn check_magic(bytes: &[u8]) -> Result<&[u8], String> {
    if let Some(body) = bytes.strip_prefix(&MAGIC) {
        return Ok(body);
    }
    if bytes.starts_with(&BINCODE_TAG) {
        return Err("the image is of the bincode format of earlier builds, which this build no longer reads \
                    (get and serialize the state again with this build)"
            .to_owned());
    }
    if MAGIC.starts_with(bytes) {
        return Err(truncated("the magic"));
    }
    Err("the image does not begin with \"FMI2RsSt\": it is not a state serialized by this exporter".to_owned())
}

/// Another model, or another build of this model, wrote the image.
fn check_identity(ours: Identity, theirs: Identity) -> Result<(), String> {
    if theirs.model_identifier != ours.model_identifier {
        return Err(format!(
            "the image is a state of model '{}' (GUID {}), this FMU is '{}' (GUID {})",
            theirs.model_identifier, theirs.guid, ours.model_identifier, ours.guid
        ));
    }
    if theirs.guid != ours.guid {
        return Err(format!(
            "the image comes from another build of '{}' (GUID {}), this build's GUID is {}",
            ours.model_identifier, theirs.guid, ours.guid
        ));
    }
    Ok(())
}

fn truncated(part: &str) -> String {
    format!("the image is truncated or corrupted: it ends in or garbles {part}")
}
