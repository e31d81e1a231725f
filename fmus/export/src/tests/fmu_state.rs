//! FMU states: snapshots restore everything they captured, serialized states survive a round
//! trip, and bytes that are not a state of this FMU (another GUID, tampered, truncated) are
//! refused by `fmi2DeSerializeFMUstate` instead of being misread.

use super::host::{toy_guid, ApiFmu, Fmu};
use super::toy::{self, vr, Other};
use crate::ffi::*;
use crate::fmi2::api;
use crate::image;
use crate::state::State::*;
use std::ptr::{null, null_mut};

fn get_state(fmu: &Fmu) -> fmi2FMUstate {
    let mut s = null_mut();
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2GetFMUstate(fmu.c, &mut s) });
    assert!(!s.is_null());
    s
}

fn free_state(fmu: &Fmu, mut s: fmi2FMUstate) {
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2FreeFMUstate(fmu.c, &mut s) });
    assert!(s.is_null());
}

fn serialize(fmu: &Fmu, s: fmi2FMUstate) -> Vec<fmi2Byte> {
    let mut size = 0;
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2SerializedFMUstateSize(fmu.c, s, &mut size) });
    let mut bytes = vec![0; size];
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2SerializeFMUstate(fmu.c, s, bytes.as_mut_ptr(), size) });
    bytes
}

fn deserialize(fmu: &Fmu, bytes: &[fmi2Byte], s: &mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    unsafe { toy::fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr(), bytes.len(), s) }
}

/// A `Toy` in step mode at t = 0.5 s with y = 0.5, and its state serialized there.
fn stepped() -> (Fmu, Vec<fmi2Byte>) {
    let fmu = Fmu::in_state(StepComplete);
    fmu.ok(fmu.set_real(&[vr::U], &[1.0]));
    fmu.ok(fmu.do_step(0.0, 0.5));
    let s = get_state(&fmu);
    let bytes = serialize(&fmu, s);
    free_state(&fmu, s);
    (fmu, bytes)
}

#[test]
fn a_serialized_state_round_trip_restores_values_and_time() {
    let (fmu, bytes) = stepped();
    fmu.ok(fmu.set_real(&[vr::RATE, vr::U], &[5.0, 2.0]));
    fmu.ok(fmu.do_step(0.5, 0.5));
    assert_eq!(fmu.reals(&[vr::Y]), [4.0]);

    let mut s = null_mut();
    fmu.ok(deserialize(&fmu, &bytes, &mut s));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2SetFMUstate(fmu.c, s) });
    assert_eq!(fmu.reals(&[vr::Y, vr::RATE, vr::U]), [0.5, 0.0, 1.0]);
    assert_eq!(fmu.time(), 0.5);
    fmu.refused(fmu.do_step(1.0, 0.5), "fmi2DoStep", &["not the current time"]);
    fmu.ok(fmu.do_step(0.5, 0.5));
    assert_eq!(fmu.reals(&[vr::Y]), [1.0]);
    free_state(&fmu, s);

    // The bytes carry the whole instance state to another instance, whatever its state.
    let fresh = Fmu::new();
    let mut s = null_mut();
    fresh.ok(deserialize(&fresh, &bytes, &mut s));
    // SAFETY: `fresh.c` is a live instance of this test, and the call takes no other pointer.
    fresh.ok(unsafe { toy::fmi2SetFMUstate(fresh.c, s) });
    assert_eq!(fresh.state(), StepComplete);
    assert_eq!(fresh.reals(&[vr::Y]), [0.5]);
    assert_eq!(fresh.time(), 0.5);
    free_state(&fresh, s);
}

#[test]
fn get_fmu_state_into_an_existing_state_overwrites_it() {
    let fmu = Fmu::in_state(StepComplete);
    let mut s = get_state(&fmu);
    let first = s;
    fmu.ok(fmu.set_real(&[vr::RATE], &[1.0]));
    fmu.ok(fmu.do_step(0.0, 1.0));
    // SAFETY: `fmu.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    fmu.ok(unsafe { toy::fmi2GetFMUstate(fmu.c, &mut s) });
    assert_eq!(s, first, "the existing state is reused");
    fmu.ok(fmu.do_step(1.0, 1.0));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2SetFMUstate(fmu.c, s) });
    assert_eq!(fmu.time(), 1.0);
    assert_eq!(fmu.reals(&[vr::Y]), [1.0]);
    free_state(&fmu, s);
}

/// An instance of [`Other`] in step mode at t = 1 s.
struct OtherFmu(ApiFmu<Other>);

impl OtherFmu {
    fn new() -> OtherFmu {
        let guid = crate::fmi2::xml::render::<Other>().expect("renders").guid;
        assert_ne!(guid.as_bytes(), toy_guid().as_bytes(), "two models, two GUIDs");
        let fmu = ApiFmu::<Other>::initializing(c"other");
        let c = fmu.c;
        // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the announced
        // length.
        unsafe {
            assert_eq!(api::exit_initialization_mode::<Other>(c), fmi2OK);
            assert_eq!(
                api::set_values::<Other, crate::calls::Real>(c, "fmi2SetReal", [vr::RATE].as_ptr(), 1, [7.0].as_ptr()),
                fmi2OK
            );
            assert_eq!(api::do_step::<Other>(c, 0.0, 1.0, fmi2True), fmi2OK);
        }
        OtherFmu(fmu)
    }

    fn serialized_state(&self) -> Vec<fmi2Byte> {
        let c = self.0.c;
        let mut s = null_mut();
        let mut size = 0;
        // SAFETY: `c` is a live instance of this test; each array or slot is a live local of at least the
        // announced length.
        unsafe {
            assert_eq!(api::get_fmu_state::<Other>(c, &mut s), fmi2OK);
            assert_eq!(api::serialized_fmu_state_size::<Other>(c, s, &mut size), fmi2OK);
            let mut bytes = vec![0; size];
            assert_eq!(api::serialize_fmu_state::<Other>(c, s, bytes.as_mut_ptr(), size), fmi2OK);
            assert_eq!(api::free_fmu_state::<Other>(c, &mut s), fmi2OK);
            bytes
        }
    }
}

/// Replaces every occurrence of `from` in `bytes` by `to` (same length).
fn replace(bytes: &[fmi2Byte], from: &[u8], to: &[u8]) -> Vec<fmi2Byte> {
    assert_eq!(from.len(), to.len());
    let mut out: Vec<u8> = bytes.iter().map(|b| *b as u8).collect();
    let at = out.windows(from.len()).position(|w| w == from).expect("the pattern occurs");
    out[at..at + to.len()].copy_from_slice(to);
    out.into_iter().map(|b| b as fmi2Byte).collect()
}

/// The bytes of the image header `identity` writes, as `fmi2Byte`s.
fn header(model_identifier: &str, guid: &str) -> Vec<fmi2Byte> {
    let header = image::header(image::Identity { model_identifier, guid }).expect("encodes");
    header.into_iter().map(|b| b as fmi2Byte).collect()
}

#[test]
fn a_state_of_another_fmu_is_refused() {
    let other = OtherFmu::new();
    let foreign = other.serialized_state();
    let other_guid = crate::fmi2::xml::render::<Other>().unwrap().guid;

    let fmu = Fmu::in_state(StepComplete);
    let mut s = null_mut();
    let words = ["a state of model 'other'", &other_guid, "this FMU is 'toy'"];
    let text = fmu.refused(deserialize(&fmu, &foreign, &mut s), "fmi2DeSerializeFMUstate", &words);
    assert!(s.is_null(), "nothing was created: {text}");

    // The same core under this FMU's header is a valid state: the header alone refused it.
    let toy_guid = toy_guid().into_string().unwrap();
    let mut relabelled = header("toy", &toy_guid);
    relabelled.extend_from_slice(&foreign[header("other", &other_guid).len()..]);
    fmu.ok(deserialize(&fmu, &relabelled, &mut s));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2SetFMUstate(fmu.c, s) });
    assert_eq!(fmu.reals(&[vr::RATE, vr::Y]), [7.0, 7.0]);
    free_state(&fmu, s);

    // And the other way round.
    let (_, own) = stepped();
    let mut s = null_mut();
    // SAFETY: `other.c` is a live instance of this test; each array or slot is a live local of at least the announced
    // length.
    let status = unsafe { api::deserialize_fmu_state::<Other>(other.0.c, own.as_ptr(), own.len(), &mut s) };
    assert_eq!(status, fmi2Error);
    assert!(s.is_null());
}

/// A state image written by the bincode format of earlier builds (a `Toy` at t = 0.5 s, taken
/// from `stepped` before the format changed): a tag (u64), the GUID, then the core.
const BINCODE_IMAGE: &[u8] = include_bytes!("bincode_toy_state.bin");

/// Each way bytes can fail to be an image of this build, and the words the refusal must say.
fn refused_images(bytes: &[fmi2Byte]) -> Vec<(&'static str, Vec<fmi2Byte>, &'static str)> {
    let guid = toy_guid();
    let mut tampered_guid = guid.as_bytes().to_vec();
    tampered_guid[5] = if tampered_guid[5] == b'0' { b'1' } else { b'0' };
    let with = |at: usize, patch: &[u8]| {
        let mut image = bytes.to_vec();
        image.splice(at..at + patch.len(), patch.iter().map(|b| *b as fmi2Byte));
        image
    };
    let magic = image::MAGIC.len();
    let mut trailing = bytes.to_vec();
    trailing.push(0);
    vec![
        ("another build's GUID", replace(bytes, guid.as_bytes(), &tampered_guid), "another build of 'toy'"),
        ("a wrong magic", with(0, b"FMI2RsSu"), "does not begin with \"FMI2RsSt\""),
        ("a newer format version", with(magic, &2u16.to_le_bytes()), "format version 2; this build reads version 1"),
        ("the bincode format", BINCODE_IMAGE.iter().map(|b| *b as fmi2Byte).collect(), "bincode format"),
        ("truncated by one byte", bytes[..bytes.len() - 1].to_vec(), "state in the image is truncated"),
        ("truncated in the magic", bytes[..4].to_vec(), "truncated or corrupted: it ends in or garbles the magic"),
        ("truncated in the version", bytes[..magic + 1].to_vec(), "garbles the format version"),
        ("truncated in the identity", bytes[..magic + 4].to_vec(), "garbles the FMU's identity"),
        // The model identifier's length (a varint) made absurd.
        ("an absurd length", with(magic + 2, &[0xff, 0xff, 0xff, 0xff, 0x0f]), "garbles the FMU's identity"),
        ("a byte after the state", trailing, "1 bytes after the state"),
        ("zeros", vec![0; bytes.len()], "not a state serialized by this exporter"),
    ]
}

#[test]
fn tampered_or_truncated_bytes_are_refused_and_leave_the_target_state_alone() {
    let (fmu, bytes) = stepped();
    assert_eq!(BINCODE_IMAGE[..8], image::BINCODE_TAG, "the bincode image's tag");

    // A target state at t = 0.5 s, which a refused call must not touch.
    let mut target = get_state(&fmu);
    fmu.ok(fmu.do_step(0.5, 0.5));
    for (what, image, words) in refused_images(&bytes) {
        let status = deserialize(&fmu, &image, &mut target);
        fmu.refused(status, "fmi2DeSerializeFMUstate", &["refused serialized state", words]);
        assert_eq!(fmu.state(), StepComplete, "{what}");
    }
    // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
    // other pointer is to a live local.
    fmu.refused(unsafe { toy::fmi2DeSerializeFMUstate(fmu.c, null(), 0, &mut target) }, "fmi2DeSerializeFMUstate", &[]);
    fmu.refused(
        // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
        // other pointer is to a live local.
        unsafe { toy::fmi2DeSerializeFMUstate(fmu.c, null(), 8, &mut target) },
        "fmi2DeSerializeFMUstate",
        &["NULL"],
    );
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2SetFMUstate(fmu.c, target) });
    assert_eq!(fmu.time(), 0.5, "the target still holds what it held");
    free_state(&fmu, target);
}

#[test]
fn state_functions_refuse_bad_pointers_and_short_buffers() {
    let fmu = Fmu::in_state(StepComplete);
    let s = get_state(&fmu);
    let size = serialize(&fmu, s).len();
    let mut short = vec![0; size - 1];
    // SAFETY: `fmu.c` is live or NULL; a NULL argument is what this call tests (refused before any use), and every
    // other pointer is to a live local.
    unsafe {
        let status = toy::fmi2SerializeFMUstate(fmu.c, s, short.as_mut_ptr(), short.len());
        fmu.refused(status, "fmi2SerializeFMUstate", &["smaller than the state"]);
        fmu.refused(toy::fmi2SerializeFMUstate(fmu.c, s, null_mut(), size), "fmi2SerializeFMUstate", &["NULL"]);
        fmu.refused(
            toy::fmi2SerializeFMUstate(fmu.c, null_mut(), short.as_mut_ptr(), 0),
            "fmi2SerializeFMUstate",
            &["NULL"],
        );
        fmu.refused(toy::fmi2SerializedFMUstateSize(fmu.c, s, null_mut()), "fmi2SerializedFMUstateSize", &["NULL"]);
        let mut n = 0;
        fmu.refused(
            toy::fmi2SerializedFMUstateSize(fmu.c, null_mut(), &mut n),
            "fmi2SerializedFMUstateSize",
            &["NULL"],
        );
        fmu.refused(toy::fmi2SetFMUstate(fmu.c, null_mut()), "fmi2SetFMUstate", &["NULL"]);
        fmu.refused(toy::fmi2GetFMUstate(fmu.c, null_mut()), "fmi2GetFMUstate", &["NULL"]);
        fmu.refused(toy::fmi2FreeFMUstate(fmu.c, null_mut()), "fmi2FreeFMUstate", &["NULL"]);
        let bytes = [0; 4];
        fmu.refused(
            toy::fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr(), 4, null_mut()),
            "fmi2DeSerializeFMUstate",
            &["NULL"],
        );
        // Freeing "no state" is a no-op (FMI 2.0 §2.1.8).
        let mut none = null_mut();
        fmu.ok(toy::fmi2FreeFMUstate(fmu.c, &mut none));
    }
    free_state(&fmu, s);
}

/// Each instance lists the states it created until they are freed, by it or by another instance
/// of the FMU, and `fmi2FreeInstance` frees the rest (the leak test under valgrind shows that
/// nothing of them is left).
#[test]
fn an_instance_tracks_its_unfreed_states_until_they_are_freed() {
    let (fmu, bytes) = stepped();
    let other = Fmu::in_state(StepComplete);
    let (a, b) = (get_state(&fmu), get_state(&fmu));
    let mut c = null_mut();
    fmu.ok(deserialize(&fmu, &bytes, &mut c));
    assert_eq!(fmu.unfreed_states(), 3);
    free_state(&fmu, a);
    free_state(&other, b);
    assert_eq!((fmu.unfreed_states(), other.unfreed_states()), (1, 0));
    // `c` stays unfreed: dropping `fmu` frees the instance, and `c` with it.
}

/// Bytes that decode but hold values no call could have set (a NaN, a parameter outside its
/// range, a stop time before the start) are refused before any use: a model must never compute
/// with them (a NaN limit makes `f64::clamp` panic).
#[test]
fn a_decodable_state_with_impossible_values_is_refused() {
    let fmu = Fmu::in_state(InitializationMode);
    fmu.ok(fmu.set_real(&[vr::GAIN], &[7.25]));
    // SAFETY: `fmu.c` is a live instance of this test, and the call takes no other pointer.
    fmu.ok(unsafe { toy::fmi2ExitInitializationMode(fmu.c) });
    let s = get_state(&fmu);
    let bytes = serialize(&fmu, s);
    free_state(&fmu, s);
    let gain = 7.25f64.to_le_bytes();
    let cases = [
        (replace(&bytes, &gain, &f64::NAN.to_le_bytes()), "corrupted serialized state: model.gain is NaN"),
        (replace(&bytes, &gain, &12.0f64.to_le_bytes()), "'gain' = 12 is outside its range [0, 10]"),
    ];
    for (image, words) in cases {
        let mut target = null_mut();
        fmu.refused(deserialize(&fmu, &image, &mut target), "fmi2DeSerializeFMUstate", &[words]);
        assert!(target.is_null());
    }
    let mut target = null_mut();
    fmu.ok(deserialize(&fmu, &bytes, &mut target));
    free_state(&fmu, target);
}
