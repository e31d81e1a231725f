use super::*;
use crate::motion::DOF_NAMES;
use crate::platform::kinematics::PlatformGeometry;
use crate::ship::profiles::{test_scale, ProfileId};
use crate::ship::rao::Hull;

/// The test-scale motion of profile `id`, as the platform plays it.
fn profile(id: ProfileId) -> HarmonicMotion {
    let p = id.profile();
    test_scale(&p.full_scale(&Hull::default(), p.seed), &PlatformGeometry::default()).unwrap().motion
}

/// The communication points t_k + h of an importer stepping 10 ms from 0 (k Δ up to rounding).
fn master_time(k: usize) -> f64 {
    k as f64 * GRID_STEP + GRID_STEP
}

fn bits(m: &DeckMotion) -> Vec<u64> {
    m.dof.iter().flat_map(|a| [a.pos, a.vel, a.acc]).map(f64::to_bits).collect()
}

#[test]
fn the_rotation_agrees_with_the_direct_sum_over_130_s() {
    // Largest error of position, velocity and acceleration of every degree of freedom over 130 s
    // at the 10 ms step, relative to the largest value of that signal: at most 1e-12 (an error in
    // the rotation, the anchoring or the δ correction shows as 1e-9 or more).
    for id in ProfileId::ALL {
        let direct = profile(id);
        let mut rotated = PhasorSum::new(direct.clone());
        let (mut error, mut peak) = ([[0.0f64; 3]; 6], [[0.0f64; 3]; 6]);
        for k in 0..13_000 {
            let tau = master_time(k);
            let (a, b) = (rotated.sample(tau), direct.sample(tau));
            for j in 0..6 {
                let (x, y) = (a.dof[j], b.dof[j]);
                for (n, (u, v)) in [(x.pos, y.pos), (x.vel, y.vel), (x.acc, y.acc)].into_iter().enumerate() {
                    error[j][n] = error[j][n].max((u - v).abs());
                    peak[j][n] = peak[j][n].max(v.abs());
                }
            }
        }
        for j in 0..6 {
            for (n, order) in ["position", "velocity", "acceleration"].iter().enumerate() {
                let relative = if peak[j][n] > 0.0 { error[j][n] / peak[j][n] } else { error[j][n] };
                println!("profile {:?} {:5} {order:12}: relative error {relative:.2e}", id, DOF_NAMES[j]);
                assert!(relative <= 1e-12, "profile {id:?} {} {order}: {relative:e}", DOF_NAMES[j]);
            }
        }
    }
}

#[test]
fn a_sample_depends_on_the_time_alone() {
    // The same grid points asked for forward, backward, repeated and scattered give the bits a
    // fresh sum gives for each point alone; a cursor rotated on from the wrong block would not.
    let motion = profile(ProfileId::One);
    let alone = |tau: f64| bits(&PhasorSum::new(motion.clone()).sample(tau));
    let indices = [0, 1, 2, 99, 100, 101, 250, 199, 150, 149, 150, 150, 1_234, 57, 12_999];
    let mut shared = PhasorSum::new(motion.clone());
    for k in indices.iter().chain(indices.iter().rev()) {
        let tau = master_time(*k);
        assert_eq!(bits(&shared.sample(tau)), alone(tau), "k = {k}");
    }
    // A saved sum (its cursor included) continues exactly as the original.
    let mut copy = shared.clone();
    for k in 13_000..13_010 {
        assert_eq!(bits(&copy.sample(master_time(k))), bits(&shared.sample(master_time(k))));
    }
}

#[test]
fn times_off_the_grid_take_the_direct_sum() {
    let motion = profile(ProfileId::Two);
    let mut rotated = PhasorSum::new(motion.clone());
    for tau in [0.005, 3.2151, 17.004_999, -0.3333, 1e13] {
        assert_eq!(bits(&rotated.sample(tau)), bits(&motion.sample(tau)), "tau = {tau}");
    }
    // Near the grid the rotation serves, negative times included.
    assert_eq!(grid_point(-2.5 + 1e-12), Some((-250, -2.5 + 1e-12 - -250.0 * GRID_STEP)));
    assert_eq!(grid_point(0.0105), None);
}

#[test]
fn every_instruction_set_gives_the_same_bits() {
    // The sums compiled for the baseline instruction set and the ones `sample` takes (AVX where
    // the processor has it) agree bit for bit, so a run does not depend on the machine (fused
    // multiply-adds or a reordered sum would show here).
    #[cfg(target_arch = "x86_64")]
    println!("AVX available: {}", std::arch::is_x86_feature_detected!("avx"));
    let mut sum = PhasorSum::new(profile(ProfileId::Three));
    for k in [0, 1_234, 5_678, 12_999] {
        sum.move_cursor(k);
        let phasors = &sum.cursor.as_ref().unwrap().phasors;
        let (dispatched, baseline) =
            (accumulate::<true>(&sum.terms, phasors), accumulate_lanes::<true>(&sum.terms, phasors));
        assert_eq!(dispatched.map(|x| x.map(f64::to_bits)), baseline.map(|x| x.map(f64::to_bits)), "k = {k}");
    }
}

#[test]
fn leaving_the_jerk_out_on_the_grid_changes_no_bit_of_the_motion() {
    // On a grid point `sample` sums without the jerk; the motion it returns must be the bits of
    // the sums with it (acc + 0·jerk against acc + 0·0), the zero-amplitude yaw included.
    for id in [ProfileId::One, ProfileId::Two, ProfileId::Three] {
        let mut sum = PhasorSum::new(profile(id));
        for k in [0, 1, 99, 100, 1_234, 12_999] {
            sum.move_cursor(k);
            let phasors = &sum.cursor.as_ref().unwrap().phasors;
            let ([pos, vel, acc, jerk], [pos0, vel0, acc0, jerk0]) =
                (accumulate::<true>(&sum.terms, phasors), accumulate::<false>(&sum.terms, phasors));
            assert!(jerk.iter().any(|j| *j != 0.0) && jerk0 == [0.0; 6], "{id:?}, k = {k}");
            let delta = 0.0;
            for j in 0..6 {
                let with = [pos[j] + delta * vel[j], vel[j] + delta * acc[j], acc[j] + delta * jerk[j]];
                let without = [pos0[j] + delta * vel0[j], vel0[j] + delta * acc0[j], acc0[j] + delta * jerk0[j]];
                assert_eq!(with.map(f64::to_bits), without.map(f64::to_bits), "{id:?}, k = {k}, dof {j}");
            }
            // And `sample` returns exactly that, as it did when it summed the jerk everywhere.
            let sampled = sum.sample(k as f64 * GRID_STEP);
            for (j, axis) in sampled.dof.iter().enumerate() {
                let full = [
                    pos[j] + delta * vel[j] - sum.motion.offsets[j],
                    vel[j] + delta * acc[j],
                    acc[j] + delta * jerk[j],
                ];
                assert_eq!([axis.pos, axis.vel, axis.acc].map(f64::to_bits), full.map(f64::to_bits), "{id:?}, k = {k}");
            }
        }
    }
}

#[test]
fn the_fused_rotation_gives_the_bits_of_the_rotation_then_the_sum() {
    // One step of the cursor with the sum in the same pass (what `sample` takes on the next grid
    // point of a block), on the baseline instruction set and the dispatched one, equals the
    // rotation by `move_cursor` followed by `accumulate`.
    let mut sum = PhasorSum::new(profile(ProfileId::One));
    for k in [0, 1, 57, 98, 1_234, 12_998] {
        sum.move_cursor(k);
        let start = sum.cursor.as_ref().unwrap().phasors.clone();
        let (mut dispatched, mut baseline) = (start.clone(), start);
        let fused = [
            rotate_accumulate::<true>(&sum.terms, &mut dispatched),
            rotate_accumulate_lanes::<true>(&sum.terms, &mut baseline),
        ];
        sum.move_cursor(k + 1);
        let phasors = &sum.cursor.as_ref().unwrap().phasors;
        let separate = accumulate_lanes::<true>(&sum.terms, phasors);
        for (sums, rotated) in fused.iter().zip([&dispatched, &baseline]) {
            assert_eq!(sums.map(|x| x.map(f64::to_bits)), separate.map(|x| x.map(f64::to_bits)), "k = {k}");
            let bits = |p: &[Complex<f64>]| p.iter().flat_map(|z| [z.re.to_bits(), z.im.to_bits()]).collect::<Vec<_>>();
            assert_eq!(bits(rotated), bits(phasors), "k = {k}");
        }
    }
}
