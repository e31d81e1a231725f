//! The FMU model driven through its variable table, as an FMI host would drive it.

use super::*;
use fmi2::harness::{get_real, instantiate, set_boolean, set_real};
use physics::math::{Vec3, STANDARD_GRAVITY};

const H: f64 = 0.01;

fn vector(m: &KnuckleBoom, prefix: &str) -> Vec3 {
    Vec3::new(
        get_real(m, &format!("{prefix}x")),
        get_real(m, &format!("{prefix}y")),
        get_real(m, &format!("{prefix}z")),
    )
}

fn run(m: &mut KnuckleBoom, seconds: f64) {
    let n = (seconds / H).round() as usize;
    for k in 0..n {
        m.do_step(k as f64 * H, H).unwrap();
    }
}

/// A crane holding `tonnes` on its rope, noise off.
fn loaded(tonnes: f64) -> KnuckleBoom {
    let mut m = instantiate::<KnuckleBoom>();
    set_boolean(&mut m, "noise", false);
    let mass = tonnes * 1000.0;
    set_real(&mut m, "cable.f0z", mass * STANDARD_GRAVITY);
    set_real(&mut m, "cable.mass", mass);
    m.initialize(0.0).unwrap();
    m
}

#[test]
fn the_variable_table_is_consistent_and_renders() {
    fmu_model::check_table(&VARIABLES).unwrap();
    let description = fmi2::xml::render::<KnuckleBoom>().unwrap();
    assert!(description.xml.contains(r#"name="cable.f0z""#));
}

#[test]
fn smoke() {
    let mut m = loaded(10.0);
    let tip = vector(&m, "tip.");
    println!(
        "tip {tip:?}, p.boom.a {} p.boom.b {} p.jib.a {} p.winch.a {} p.winch.b {}",
        get_real(&m, "p.boom.a"),
        get_real(&m, "p.boom.b"),
        get_real(&m, "p.jib.a"),
        get_real(&m, "p.winch.a"),
        get_real(&m, "p.winch.b")
    );
    run(&mut m, 60.0);
    let drift = vector(&m, "tip.") - tip;
    println!("drift {drift:?} lp {}", get_real(&m, "lp"));
    set_real(&mut m, "spool.boom", 0.5);
    run(&mut m, 3.0);
    println!(
        "after luffing: boom {} rate {} stroke rate {} tip {:?}",
        get_real(&m, "joint.boom"),
        get_real(&m, "joint.boom_dot"),
        get_real(&m, "stroke.boom_dot"),
        vector(&m, "tip.")
    );
    set_real(&mut m, "spool.boom", 0.0);
    set_real(&mut m, "spool.winch", -0.5);
    run(&mut m, 3.0);
    println!(
        "after hoisting: lp {} lp_dot {} p.winch.a {} tension {}",
        get_real(&m, "lp"),
        get_real(&m, "lp_dot"),
        get_real(&m, "p.winch.a"),
        get_real(&m, "tension")
    );
}
