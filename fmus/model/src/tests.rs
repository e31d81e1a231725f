use crate::{check_table, table, table_len, xyz, Causality, Value, Variability, Variable};

#[derive(Default)]
struct Toy {
    gain: f64,
    u: f64,
    du: Option<f64>,
    pos: Vec3,
    mode: i32,
    on: bool,
    file: String,
}

#[derive(Default)]
struct Vec3 {
    x: f64,
    y: f64,
    z: f64,
}

/// The start values of a `Toy`'s vector (the constant a model starts its fields from).
struct Start {
    pos: Vec3,
}

const START: Start = Start { pos: Vec3 { x: 1.0, y: 2.0, z: 3.0 } };

/// The components of a vector as an array, as `physics::math::components` gives them to `xyz!`.
const fn components(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

type Real = crate::Real<Toy>;
type Integer = crate::Integer<Toy>;
type Boolean = crate::Boolean<Toy>;
type Text = crate::Text<Toy>;
type V = Variable<Toy>;

const GROUPS: &[&[V]] = &[
    &[
        crate::field!(Real::parameter(0, "gain"), unit: "1", start: 2.0, range: (0.0, 10.0), doc: "Gain",
            field: m => m.gain),
        Real::input(1, "u")
            .unit("m")
            .start(0.5)
            .doc("Input")
            .get(|m| m.u)
            .set(|m, v| m.u = v)
            .derivative(|m, d| m.du = d),
        Integer::tunable(2, "mode").start(1).range(0, 2).doc("Mode").get(|m| m.mode).set(|m, v| m.mode = v),
        Boolean::parameter(3, "on").start(true).doc("On").get(|m| m.on).set(|m, v| m.on = v),
        Boolean::output(4, "positive").doc("u > 0").get(|m| m.u > 0.0),
        Text::parameter(5, "file").start("a.csv").doc("File").get(|m| &m.file).set(|m, v| m.file = v.to_owned()),
    ],
    &xyz!(Real::held_input(10, "pos."),
        unit: "m",
        range: (-5.0, 5.0),
        doc: ["Position x", "Position y", "Position z (down)"],
        field: (m, START).pos),
    &xyz!(Real::output(20, "pos.v"),
        unit: "m/s",
        doc: ("Velocity " + axis + ", W"),
        get: |m| m.pos),
];

static TABLE: [V; table_len(GROUPS)] = table(GROUPS);

fn row(name: &str) -> &'static V {
    TABLE.iter().find(|v| v.name == name).unwrap_or_else(|| panic!("no {name}"))
}

#[test]
fn groups_join_into_one_table_in_order() {
    let names: Vec<&str> = TABLE.iter().map(|v| v.name).collect();
    let want = ["gain", "u", "mode", "on", "positive", "file", "pos.x", "pos.y", "pos.z", "pos.vx", "pos.vy", "pos.vz"];
    assert_eq!(names, want);
    check_table(&TABLE).unwrap();
}

#[test]
fn unit_start_and_range_land_in_the_real_value() {
    let gain = row("gain");
    assert_eq!((gain.vr, gain.description), (0, "Gain"));
    assert_eq!((gain.causality, gain.variability), (Causality::Parameter, Variability::Fixed));
    let Value::Real { unit, start, min, max, set, derivative, .. } = gain.value else { panic!("a Real") };
    assert_eq!((unit, start, min, max), ("1", 2.0, Some(0.0), Some(10.0)));
    assert!(set.is_some() && derivative.is_none(), "a parameter is set, never interpolated");
}

#[test]
fn each_kind_gets_its_causality_variability_and_accessors() {
    let kinds = |name| (row(name).causality, row(name).variability);
    assert_eq!(kinds("u"), (Causality::Input, Variability::Continuous));
    assert_eq!(kinds("mode"), (Causality::Parameter, Variability::Tunable));
    assert_eq!(kinds("on"), (Causality::Parameter, Variability::Fixed));
    assert_eq!(kinds("positive"), (Causality::Output, Variability::Discrete));
    assert_eq!(kinds("pos.vx"), (Causality::Output, Variability::Continuous));
    assert!(matches!(row("u").value, Value::Real { set: Some(_), derivative: Some(_), .. }), "interpolated");
    assert!(matches!(row("pos.y").value, Value::Real { set: Some(_), derivative: None, .. }), "held");
    assert!(matches!(row("pos.vy").value, Value::Real { set: None, derivative: None, .. }), "an output");
    assert!(matches!(row("mode").value, Value::Integer { start: 1, min: Some(0), max: Some(2), .. }));
    assert!(matches!(row("on").value, Value::Boolean { start: true, set: Some(_), .. }));
    assert!(matches!(row("positive").value, Value::Boolean { set: None, .. }));
    assert!(matches!(row("file").value, Value::String { start: "a.csv", set: Some(_), .. }));
}

#[test]
fn accessors_reach_the_fields_they_name() {
    let mut m = Toy::default();
    let (Value::Real { set: Some(set), .. }, Value::Real { get, .. }) = (row("pos.z").value, row("pos.vz").value)
    else {
        panic!("Reals")
    };
    set(&mut m, 4.5);
    assert_eq!((m.pos.x, m.pos.y, m.pos.z), (0.0, 0.0, 4.5));
    assert_eq!(get(&m), 4.5);
    let (Value::Real { set: Some(set), .. }, Value::Real { get, .. }) = (row("gain").value, row("gain").value) else {
        panic!("a Real parameter")
    };
    set(&mut m, 7.0);
    assert_eq!((m.gain, get(&m)), (7.0, 7.0));
    let Value::Real { derivative: Some(derivative), .. } = row("u").value else { panic!("interpolated") };
    derivative(&mut m, Some(0.25));
    assert_eq!(m.du, Some(0.25));
}

#[test]
fn a_triple_numbers_names_and_describes_each_axis() {
    let rows: Vec<(u32, &str, &str)> = TABLE[6..9].iter().map(|v| (v.vr, v.name, v.description)).collect();
    assert_eq!(rows, [(10, "pos.x", "Position x"), (11, "pos.y", "Position y"), (12, "pos.z", "Position z (down)")]);
    let starts: Vec<(f64, Option<f64>)> = TABLE[6..9]
        .iter()
        .map(|v| match v.value {
            Value::Real { start, max, .. } => (start, max),
            _ => panic!("Reals"),
        })
        .collect();
    assert_eq!(starts, [(1.0, Some(5.0)), (2.0, Some(5.0)), (3.0, Some(5.0))]);
}

#[test]
fn a_triple_with_one_text_puts_the_axis_into_it() {
    let rows: Vec<(u32, &str, &str)> = TABLE[9..].iter().map(|v| (v.vr, v.name, v.description)).collect();
    assert_eq!(
        rows,
        [(20, "pos.vx", "Velocity x, W"), (21, "pos.vy", "Velocity y, W"), (22, "pos.vz", "Velocity z, W")]
    );
}

/// A row written as a struct literal, as the builder would never build it.
fn literal(causality: Causality, unit: &'static str, set: Option<fn(&mut Toy, f64)>) -> V {
    let value = Value::<Toy>::Real { unit, start: 0.0, min: None, max: None, get: |m| m.gain, set, derivative: None };
    Variable { vr: 0, name: "x", description: "x", causality, variability: Variability::Continuous, value }
}

#[test]
fn the_table_check_refuses_what_the_builder_cannot_build() {
    let set: Option<fn(&mut Toy, f64)> = Some(|m, v| m.gain = v);
    let refusal = |row: V| check_table(&[row]).unwrap_err();
    assert!(refusal(literal(Causality::Input, "m", None)).contains("no setter"));
    assert!(refusal(literal(Causality::Output, "m", set)).contains("a setter it never gets"));
    assert!(refusal(literal(Causality::Input, "", set)).contains("without a unit"));
    let mut outside = literal(Causality::Input, "m", set);
    outside.value =
        Value::Real { unit: "m", start: 2.0, min: Some(0.0), max: Some(1.0), get: |_| 0.0, set, derivative: None };
    assert!(refusal(outside).contains("outside"));
    check_table(&[literal(Causality::Input, "m", set)]).unwrap();
}

#[test]
fn the_table_check_refuses_duplicates() {
    let mut twin = TABLE[0];
    twin.name = "twin";
    assert!(check_table(&[TABLE[0], twin]).unwrap_err().contains("duplicate Real value reference 0"));
    let mut same_name = TABLE[1];
    same_name.vr = 99;
    assert!(check_table(&[TABLE[1], same_name]).unwrap_err().contains("duplicate variable name u"));
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Sea {
    Calm,
    Wave(Height),
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Height {
    Low,
    High,
}

crate::codes! {
    /// Codes that start at 1, with values that carry a value.
    SeaCodes: Sea { Sea::Calm => 1, Sea::Wave(Height::Low) => 2, Sea::Wave(Height::High) => 3 }
}

crate::codes! {
    /// Codes of a `bool` setting.
    FlagCodes: bool { false => 0, true => 1 }
}

#[test]
fn codes_convert_both_ways_and_span_their_range() {
    const START: i32 = SeaCodes::code(Sea::Wave(Height::Low));
    assert_eq!(START, 2);
    assert_eq!((SeaCodes::MIN, SeaCodes::MAX), (1, 3));
    for code in SeaCodes::MIN..=SeaCodes::MAX {
        let value = SeaCodes::decode(code).unwrap();
        assert_eq!(SeaCodes::code(value), code, "{value:?}");
    }
    assert_eq!(SeaCodes::decode(0), None);
    assert_eq!(SeaCodes::decode(4), None);
    assert_eq!((FlagCodes::code(true), FlagCodes::decode(0)), (1, Some(false)));
    let mut flag = false;
    FlagCodes::set(&mut flag, FlagCodes::MAX);
    assert!(flag);
    assert_eq!((FlagCodes::MIN, FlagCodes::MAX), (0, 1));
}

#[test]
fn a_setter_writes_a_code_and_keeps_the_value_on_an_unknown_one() {
    let mut sea = Sea::Calm;
    SeaCodes::set(&mut sea, 3);
    assert_eq!(sea, Sea::Wave(Height::High));
    SeaCodes::set(&mut sea, 7);
    assert_eq!(sea, Sea::Wave(Height::High));
}

#[test]
fn the_range_of_codes_is_checked() {
    assert_eq!(crate::codes::range(&[2, 0, 1]), (0, 2));
    let refused = |codes: &'static [i32]| std::panic::catch_unwind(|| crate::codes::range(codes)).is_err();
    assert!(refused(&[0, 2]), "a gap");
    assert!(refused(&[0, 1, 1]), "a shared code");
    assert!(refused(&[]), "no codes");
}

/// A model with an enumeration parameter, written with `coded!`.
struct Moored {
    sea: Sea,
}

type MooredInteger = crate::Integer<Moored>;

static SEA: Variable<Moored> = crate::coded!(MooredInteger::tunable(0, "sea"), SeaCodes, start: Sea::Calm,
    doc: "Sea state", value: |m| m.sea);

#[test]
fn a_coded_row_starts_ranges_and_accesses_by_the_codes() {
    let Value::Integer { start, min, max, get, set: Some(set) } = SEA.value else { panic!("an Integer parameter") };
    assert_eq!((start, min, max), (1, Some(1), Some(3)));
    let mut moored = Moored { sea: Sea::Calm };
    set(&mut moored, 3);
    assert_eq!((moored.sea, get(&moored)), (Sea::Wave(Height::High), 3));
    assert_eq!(SEA.variability, Variability::Tunable);
}
