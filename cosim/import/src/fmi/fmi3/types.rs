//! What an FMI 3.0 model description tells the adapter about the rows that are not direct
//! scalars: their FMI 3.0 type ([`Fmi3Type`]), where each one lives ([`Fmi3Element`]) and its
//! start value ([`Start`]). `crate::fmu` lists them, [`super::elements`] reaches them.

/// The FMI 3.0 type of a variable the adapter reaches through a conversion or as an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fmi3Type {
    Float64,
    Float32,
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Boolean,
    /// An enumeration: an Int64 on the ABI.
    Enumeration,
}

impl Fmi3Type {
    pub fn of(tag: &str) -> Option<Fmi3Type> {
        Some(match tag {
            "Float64" => Fmi3Type::Float64,
            "Float32" => Fmi3Type::Float32,
            "Int8" => Fmi3Type::Int8,
            "UInt8" => Fmi3Type::UInt8,
            "Int16" => Fmi3Type::Int16,
            "UInt16" => Fmi3Type::UInt16,
            "Int32" => Fmi3Type::Int32,
            "UInt32" => Fmi3Type::UInt32,
            "Int64" => Fmi3Type::Int64,
            "UInt64" => Fmi3Type::UInt64,
            "Boolean" => Fmi3Type::Boolean,
            "Enumeration" => Fmi3Type::Enumeration,
            _ => return None,
        })
    }

    /// The range of an integer type (`None` for the others).
    pub fn integer_range(self) -> Option<(i128, i128)> {
        Some(match self {
            Fmi3Type::Int8 => (i8::MIN.into(), i8::MAX.into()),
            Fmi3Type::UInt8 => (0, u8::MAX.into()),
            Fmi3Type::Int16 => (i16::MIN.into(), i16::MAX.into()),
            Fmi3Type::UInt16 => (0, u16::MAX.into()),
            Fmi3Type::Int32 => (i32::MIN.into(), i32::MAX.into()),
            Fmi3Type::UInt32 => (0, u32::MAX.into()),
            Fmi3Type::Int64 | Fmi3Type::Enumeration => (i64::MIN.into(), i64::MAX.into()),
            Fmi3Type::UInt64 => (0, u64::MAX.into()),
            Fmi3Type::Float64 | Fmi3Type::Float32 | Fmi3Type::Boolean => return None,
        })
    }

    /// The element name in FMI 3.0.
    pub fn name(self) -> &'static str {
        match self {
            Fmi3Type::Float64 => "Float64",
            Fmi3Type::Float32 => "Float32",
            Fmi3Type::Int8 => "Int8",
            Fmi3Type::UInt8 => "UInt8",
            Fmi3Type::Int16 => "Int16",
            Fmi3Type::UInt16 => "UInt16",
            Fmi3Type::Int32 => "Int32",
            Fmi3Type::UInt32 => "UInt32",
            Fmi3Type::Int64 => "Int64",
            Fmi3Type::UInt64 => "UInt64",
            Fmi3Type::Boolean => "Boolean",
            Fmi3Type::Enumeration => "Enumeration",
        }
    }
}

/// How the adapter reaches one row that is not a direct FMI 3.0 scalar: element `index` of the
/// `size` values of the FMI 3.0 variable `fmi3_value_reference`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fmi3Element {
    /// The row's value reference (synthetic for array elements).
    pub value_reference: u32,
    pub name: String,
    pub fmi3_value_reference: u32,
    pub fmi3_type: Fmi3Type,
    pub index: usize,
    pub size: usize,
    /// The start value, which the adapter keeps for the other elements of an array it sets
    /// whole (arrays are set whole in FMI 3.0), at the width of the FMI 3.0 type (an integer
    /// start may not fit the row).
    pub start: Option<Start>,
}

/// A start value of an element at the width of its FMI 3.0 type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    Float(f64),
    Integer(i128),
    Boolean(bool),
}
