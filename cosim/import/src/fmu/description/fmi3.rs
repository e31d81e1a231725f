//! FMI 3.0 model descriptions, read into the rows an FMI 2.0 description gives
//! ([`ScalarVariable`]), so that everything above the importer handles both versions alike.
//!
//! - Float64, Int32, Boolean and String scalars are rows of the matching FMI 2.0 type (Real,
//!   Integer, Boolean, String) under their own value reference.
//! - The other numeric types are converted where no value is lost: Float32 reads as a Real (an
//!   exact widening), Int8, UInt8, Int16, UInt16 as Integer; UInt32, Int64, UInt64 and
//!   enumerations (Int64 in FMI 3.0) as Integer, where a value outside the 32-bit range is
//!   refused when it is read or set. Setting a Float32 to a value that is not exactly a
//!   float32, or a small integer type to a value outside its range, is refused.
//! - An array with fixed dimensions (`<Dimension start=…>`) is its elements, each a row named
//!   `x[1]`, `x[2]`, … (1-based; `m[1,1]`, `m[1,2]`, … row-major for more dimensions, the
//!   structured naming convention of FMI 3.0 §2.4.7.2) under a value reference of its own,
//!   numbered after the largest one the FMU uses.
//! - An array may have at most [`MAX_ARRAY_ELEMENTS`] elements, and a description at most
//!   [`MAX_SCALAR_VARIABLES`] rows with every array's elements counted: both are checked from the
//!   declared dimensions before any element is made, so a description of a few bytes cannot ask
//!   for gigabytes.
//! - Binary and Clock variables, String arrays and arrays sized by a structural parameter are
//!   refused by name: no FMI 2.0 row can carry them. Structural parameters themselves are read
//!   (as calculated parameters: only Configuration Mode, which this importer never enters, may
//!   set them).
//!
//! Every variable that is not a direct scalar is also listed as an [`Fmi3Element`]: how the
//! adapter ([`crate::fmi::fmi3`]) reaches it.

use std::collections::HashMap;

use roxmltree::Node;

use super::parser::{parse_start, real_unit, Parser};
use super::{Causality, CoSimulation, Initial, ModelDescriptionError, ScalarVariable, Variability};
use crate::fmi::fmi3::{Fmi3Element, Fmi3Type, Start};
use crate::value::{Value, VariableType};

/// Most elements one FMI 3.0 array variable may have: far more than any co-simulation port
/// carries, and each element becomes a row of its own (a name, a value reference, an element
/// record), a few hundred bytes apiece.
pub const MAX_ARRAY_ELEMENTS: usize = 100_000;

/// Most rows one FMI 3.0 description may declare, every array counted by its elements: about
/// half a gigabyte of rows at the most.
pub const MAX_SCALAR_VARIABLES: usize = 1_000_000;

/// The FMI 2.0 type an FMI 3.0 type's values are exchanged as.
fn row_type(fmi3_type: Fmi3Type) -> VariableType {
    match fmi3_type {
        Fmi3Type::Float64 | Fmi3Type::Float32 => VariableType::Real,
        Fmi3Type::Boolean => VariableType::Boolean,
        _ => VariableType::Integer,
    }
}

/// A start value as an FMI 2.0-style row holds it (`None`: an integer outside 32 bits).
fn row_value(start: Start) -> Option<Value> {
    match start {
        Start::Float(v) => Some(Value::Real(v)),
        Start::Integer(v) => i32::try_from(v).ok().map(Value::Integer),
        Start::Boolean(v) => Some(Value::Boolean(v)),
    }
}

/// One FMI 3.0 variable element, read but not yet numbered.
struct Declared {
    row: ScalarVariable,
    fmi3_type: Option<Fmi3Type>,
    dimensions: Vec<usize>,
    starts: Vec<String>,
}

impl<'a, 'input> Parser<'a, 'input> {
    /// FMI 3.0 `<CoSimulation>`: the capabilities this importer reads, under their FMI 3.0
    /// names. FMI 3.0 has no input derivatives, so `can_interpolate_inputs` is false.
    pub(super) fn co_simulation_3(&self, node: Node) -> Result<CoSimulation, ModelDescriptionError> {
        let mut co_simulation = self.co_simulation_2(node)?;
        co_simulation.can_interpolate_inputs = false;
        co_simulation.can_get_and_set_fmu_state = self.boolean(node, "canGetAndSetFMUState")?;
        co_simulation.can_serialize_fmu_state = self.boolean(node, "canSerializeFMUState")?;
        co_simulation.provides_directional_derivative = self.boolean(node, "providesDirectionalDerivatives")?;
        Ok(co_simulation)
    }

    /// FMI 3.0 units of `<TypeDefinitions>/<Float64Type unit=...>` (and Float32), by type name.
    pub(super) fn type_units_3(&self, root: Node) -> Result<HashMap<String, String>, ModelDescriptionError> {
        let mut units = HashMap::new();
        if let Some(definitions) = self.child(root, "TypeDefinitions")? {
            let float_types =
                definitions.children().filter(|c| c.has_tag_name("Float64Type") || c.has_tag_name("Float32Type"));
            for typed in float_types {
                if let Some(unit) = typed.attribute("unit") {
                    units.insert(self.required(typed, "name")?.to_string(), unit.to_string());
                }
            }
        }
        Ok(units)
    }

    /// The rows and elements of `<ModelVariables>`, arrays expanded (see the module
    /// documentation).
    pub(super) fn variables_3(
        &self,
        model_variables: Node,
        units: &HashMap<String, String>,
    ) -> Result<(Vec<ScalarVariable>, Vec<Fmi3Element>), ModelDescriptionError> {
        let nodes: Vec<Node> = model_variables.children().filter(|c| c.is_element()).collect();
        let declared = nodes.iter().map(|node| self.declared_3(*node, units)).collect::<Result<Vec<_>, _>>()?;
        // The rows the arrays expand into, counted before any is made.
        let total =
            declared.iter().fold(0usize, |total, d| total.saturating_add(d.dimensions.iter().product::<usize>()));
        if total > MAX_SCALAR_VARIABLES {
            return Err(self.error(
                model_variables,
                format!(
                    "the model variables are {total} scalars with every array's elements counted, more than the \
                     {MAX_SCALAR_VARIABLES} this importer reads from one FMU"
                ),
            ));
        }
        let mut next_synthetic = declared.iter().map(|d| d.row.value_reference).max().map_or(0, |vr| u64::from(vr) + 1);
        let (mut rows, mut elements) = (Vec::new(), Vec::new());
        let mut names = std::collections::HashSet::new();
        for (node, declared) in nodes.iter().zip(declared) {
            let size: usize = declared.dimensions.iter().product();
            let expanded = self.expand_3(*node, declared, size, &mut next_synthetic)?;
            for (row, element) in expanded {
                if !names.insert(row.name.clone()) {
                    return Err(self.error(*node, format!("variable name {:?} is declared twice", row.name)));
                }
                rows.push(row);
                elements.extend(element);
            }
        }
        Ok((rows, elements))
    }

    /// The rows of one declared variable: itself, or its elements.
    fn expand_3(
        &self,
        node: Node,
        declared: Declared,
        size: usize,
        next_synthetic: &mut u64,
    ) -> Result<Vec<(ScalarVariable, Option<Fmi3Element>)>, ModelDescriptionError> {
        let Declared { row, fmi3_type, dimensions, starts } = declared;
        let name = row.name.clone();
        let Some(fmi3_type) = fmi3_type else { return Ok(vec![(row, None)]) };
        let parse = |text: &str| {
            parse_start_3(fmi3_type, text).ok_or_else(|| {
                self.error(node, format!("variable {name:?}: start {text:?} is not a valid {}", fmi3_type.name()))
            })
        };
        let is_array = !dimensions.is_empty();
        if !is_array {
            let start = starts.first().map(|t| parse(t)).transpose()?;
            let element = element_of(&row, fmi3_type, start);
            return Ok(vec![(ScalarVariable { start: start.and_then(row_value), ..row }, element)]);
        }
        if !(starts.is_empty() || starts.len() == 1 || starts.len() == size) {
            return Err(
                self.error(node, format!("array {name:?} has {size} elements but {} start values", starts.len()))
            );
        }
        (0..size)
            .map(|index| {
                let vr = u32::try_from(*next_synthetic)
                    .map_err(|_| self.error(node, "no value reference is left for the elements of the arrays"))?;
                *next_synthetic += 1;
                let start = match starts.len() {
                    0 => None,
                    1 => Some(parse(&starts[0])?),
                    _ => Some(parse(&starts[index])?),
                };
                let element = ScalarVariable {
                    name: format!("{name}[{}]", subscripts(&dimensions, index)),
                    value_reference: vr,
                    start: start.and_then(row_value),
                    ..row.clone()
                };
                let access = Fmi3Element {
                    value_reference: vr,
                    name: element.name.clone(),
                    fmi3_value_reference: row.value_reference,
                    fmi3_type,
                    index,
                    size,
                    start,
                };
                Ok((element, Some(access)))
            })
            .collect()
    }

    /// One FMI 3.0 variable element as a row (start values still as text).
    fn declared_3(&self, node: Node, units: &HashMap<String, String>) -> Result<Declared, ModelDescriptionError> {
        let tag = node.tag_name().name();
        let name = self.required(node, "name")?.to_string();
        let (variable_type, fmi3_type) = match (tag, Fmi3Type::of(tag)) {
            ("String", _) => (VariableType::String, None),
            (_, Some(t)) => (row_type(t), Some(t)),
            ("Binary" | "Clock", _) => {
                return Err(self.error(
                    node,
                    format!("variable {name:?} is an FMI 3.0 {tag}, which this importer cannot exchange"),
                ))
            }
            _ => return Err(self.error(node, format!("unexpected <{tag}> in <ModelVariables>"))),
        };
        let dimensions = self.dimensions_3(node, &name)?;
        if variable_type == VariableType::String && !dimensions.is_empty() {
            return Err(
                self.error(node, format!("variable {name:?} is a String array, which this importer cannot exchange"))
            );
        }
        let value_reference = match self.parsed::<u32>(node, "valueReference", "an unsigned 32-bit integer")? {
            Some(vr) => vr,
            None => return Err(self.error(node, format!("variable {name:?} has no valueReference"))),
        };
        let declared_type = node.attribute("declaredType").map(String::from);
        let start_text = match variable_type {
            VariableType::String => {
                node.children().find(|c| c.has_tag_name("Start")).and_then(|c| c.attribute("value"))
            }
            _ => node.attribute("start"),
        };
        let starts: Vec<String> = match (variable_type, start_text) {
            (_, None) => Vec::new(),
            (VariableType::String, Some(text)) => vec![text.to_string()],
            (_, Some(text)) => text.split_whitespace().map(String::from).collect(),
        };
        // Direct scalars (Float64, Int32, Boolean scalars, Strings) are rows as they are.
        let direct = dimensions.is_empty()
            && matches!(fmi3_type, None | Some(Fmi3Type::Float64 | Fmi3Type::Int32 | Fmi3Type::Boolean));
        let start =
            match (direct, starts.first()) {
                (true, Some(text)) => Some(parse_start(variable_type, text).ok_or_else(|| {
                    self.error(node, format!("variable {name:?}: start={text:?} is not a valid {tag}"))
                })?),
                _ => None,
            };
        let unit = real_unit(variable_type, node, declared_type.as_ref(), units);
        let row = ScalarVariable {
            name,
            value_reference,
            description: node.attribute("description").map(String::from),
            causality: self.causality_3(node)?,
            variability: self.keyword(node, "variability", Variability::KEYWORDS)?.unwrap_or(match variable_type {
                VariableType::Real => Variability::Continuous,
                _ => Variability::Discrete,
            }),
            initial: self.keyword::<Initial>(node, "initial", Initial::KEYWORDS)?,
            variable_type,
            start,
            unit,
            declared_type,
            range: (node.attribute("min").map(String::from), node.attribute("max").map(String::from)),
        };
        Ok(Declared { row, fmi3_type: if direct { None } else { fmi3_type }, dimensions, starts })
    }

    /// FMI 3.0's causalities: FMI 2.0's, plus `structuralParameter` (FMI 3.0 §2.4.7.4), which
    /// only Configuration Mode may set; this importer never enters it, so such a parameter is
    /// read like a calculated parameter and never set.
    fn causality_3(&self, node: Node) -> Result<Causality, ModelDescriptionError> {
        if node.attribute("causality") == Some("structuralParameter") {
            return Ok(Causality::CalculatedParameter);
        }
        Ok(self.keyword(node, "causality", Causality::KEYWORDS)?.unwrap_or_default())
    }

    /// The fixed dimensions of an array (empty for a scalar), whose product is at most
    /// [`MAX_ARRAY_ELEMENTS`].
    fn dimensions_3(&self, node: Node, name: &str) -> Result<Vec<usize>, ModelDescriptionError> {
        let dimensions: Vec<usize> = node
            .children()
            .filter(|c| c.has_tag_name("Dimension"))
            .map(|dimension| match self.parsed::<usize>(dimension, "start", "a size")? {
                Some(size) if size > 0 => Ok(size),
                Some(_) => Err(self.error(dimension, format!("array {name:?} has an empty dimension"))),
                None => Err(self.error(
                    dimension,
                    format!(
                        "array {name:?} is sized by a structural parameter, which this importer cannot follow \
                         (only fixed dimensions, <Dimension start=\"n\"/>)"
                    ),
                )),
            })
            .collect::<Result<_, _>>()?;
        // Checked before the elements are made: the product of sizes from the file may be huge or
        // overflow.
        let elements = dimensions.iter().try_fold(1usize, |n, size| n.checked_mul(*size));
        match elements {
            Some(n) if n <= MAX_ARRAY_ELEMENTS => Ok(dimensions),
            _ => {
                let sizes = dimensions.iter().map(usize::to_string).collect::<Vec<_>>().join(" x ");
                let count = elements.map_or_else(|| format!("more than {}", usize::MAX), |n| n.to_string());
                Err(self.error(
                    node,
                    format!(
                        "array {name:?} has {count} elements ({sizes}), more than the {MAX_ARRAY_ELEMENTS} this \
                         importer reads per array"
                    ),
                ))
            }
        }
    }
}

/// The element record of a converted scalar.
fn element_of(row: &ScalarVariable, fmi3_type: Fmi3Type, start: Option<Start>) -> Option<Fmi3Element> {
    Some(Fmi3Element {
        value_reference: row.value_reference,
        name: row.name.clone(),
        fmi3_value_reference: row.value_reference,
        fmi3_type,
        index: 0,
        size: 1,
        start,
    })
}

/// `1,2` for element `index` (row-major) of an array with `dimensions`, 1-based.
fn subscripts(dimensions: &[usize], index: usize) -> String {
    let mut rest = index;
    let mut parts = vec![0; dimensions.len()];
    for (part, size) in parts.iter_mut().zip(dimensions).rev() {
        *part = rest % size + 1;
        rest /= size;
    }
    parts.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
}

/// A start value of a converted type (`None`: not a value of that type).
fn parse_start_3(fmi3_type: Fmi3Type, text: &str) -> Option<Start> {
    match (fmi3_type, fmi3_type.integer_range()) {
        (_, Some((low, high))) => {
            let value: i128 = text.trim().parse().ok()?;
            (low..=high).contains(&value).then_some(Start::Integer(value))
        }
        (Fmi3Type::Boolean, _) => match parse_start(VariableType::Boolean, text)? {
            Value::Boolean(v) => Some(Start::Boolean(v)),
            _ => None,
        },
        _ => match parse_start(VariableType::Real, text)? {
            Value::Real(v) => Some(Start::Float(v)),
            _ => None,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::subscripts;

    #[test]
    fn element_names_are_one_based_and_row_major() {
        assert_eq!(subscripts(&[3], 0), "1");
        assert_eq!(subscripts(&[3], 2), "3");
        let names: Vec<String> = (0..6).map(|i| subscripts(&[2, 3], i)).collect();
        assert_eq!(names, ["1,1", "1,2", "1,3", "2,1", "2,2", "2,3"]);
    }
}
