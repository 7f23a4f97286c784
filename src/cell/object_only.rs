//! Records read from JSON objects only.
//!
//! serde's derived `Deserialize` also takes a JSON array of a struct's fields in declaration
//! order: `[0.0, 1.0, 2.0, 0.5]` would be read as a sample with `t`, `x`, `y` and `vx`, and
//! θ = 0, silently. Every record of the file formats is documented as an object, so each
//! one derives its field-reading code with `#[serde(remote = "Self")]` (an inherent
//! `deserialize`) and gets its `Deserialize` from [`object_only!`], which asks the
//! deserializer for a map and refuses anything else with the record's `expecting` text.

/// `impl Deserialize` for a `#[serde(remote = "Self")]` struct that accepts a JSON object
/// only; the error for anything else says what was expected.
macro_rules! object_only {
    ($record:ident, $expecting:literal) => {
        impl<'de> serde::Deserialize<'de> for $record {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Object;
                impl<'de> serde::de::Visitor<'de> for Object {
                    type Value = $record;
                    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                        f.write_str($expecting)
                    }
                    fn visit_map<A: serde::de::MapAccess<'de>>(
                        self,
                        map: A,
                    ) -> Result<$record, A::Error> {
                        // The derived (inherent) reader, fed the object's entries.
                        $record::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    }
                }
                d.deserialize_map(Object)
            }
        }
    };
}

pub(super) use object_only;
