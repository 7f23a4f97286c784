//! Records read from JSON objects only, with no key but their own.
//!
//! serde's derived `Deserialize` also takes a JSON array of a struct's fields in declaration
//! order: `[0.0, 1.0, 2.0, 0.5]` would be read as a sample with `t`, `x`, `y` and `vx`, and
//! θ = 0, silently. Every record of the file formats is documented as an object, so each
//! one derives its field-reading code with `#[serde(remote = "Self")]` (an inherent
//! `deserialize`) and gets its `Deserialize` from [`object_only!`], which asks the
//! deserializer for a map and refuses anything else with the record's `expecting` text.
//!
//! A key the record does not know is an error too (each record denies unknown fields: a
//! typo such as `delat` must not leave δ at its default), except keys that begin with `_`,
//! which [`Commented`] skips with their values: room for comments and other tools' data.

use serde::de::{DeserializeSeed, IgnoredAny, IntoDeserializer, MapAccess};

/// The entries of a JSON object without those whose key begins with `_`.
pub(super) struct Commented<A>(pub A);

impl<'de, A: MapAccess<'de>> MapAccess<'de> for Commented<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        while let Some(key) = self.0.next_key::<String>()? {
            if key.starts_with('_') {
                self.0.next_value::<IgnoredAny>()?;
                continue;
            }
            let key: serde::de::value::StringDeserializer<A::Error> = key.into_deserializer();
            return seed.deserialize(key).map(Some);
        }
        Ok(None)
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, A::Error> {
        self.0.next_value_seed(seed)
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

/// `impl Deserialize` for a `#[serde(remote = "Self")]` struct that accepts a JSON object
/// only; the error for anything else says what was expected. Keys beginning with `_` are
/// skipped ([`Commented`]).
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
                        let map = $crate::cell::object_only::Commented(map);
                        $record::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    }
                }
                d.deserialize_map(Object)
            }
        }
    };
}

pub(super) use object_only;

/// serde's refusal of an unknown field ("unknown field `delat`, expected one of `delta`,
/// `robots`, …") as [`unknown`] says it, after the key itself. `None` for any other message.
pub(super) fn unknown_key(message: &str) -> Option<(String, String)> {
    let rest = message.strip_prefix("unknown field `")?;
    let (key, rest) = rest.split_once('`')?;
    let known: Vec<&str> = rest.split('`').skip(1).step_by(2).collect();
    // serde_json's place in the text, when it gives one.
    let place = message.rfind(" at line ").map_or("", |i| &message[i..]);
    Some((key.to_owned(), format!("{}{place}", unknown(key, &known))))
}

/// The first of `keys` that is neither one of `known` nor begins with `_`, and why it is
/// refused ([`unknown`]).
pub(super) fn first_unknown<'k>(
    keys: impl IntoIterator<Item = &'k str>,
    known: &[&str],
) -> Option<(String, String)> {
    let key = keys
        .into_iter()
        .find(|k| !k.starts_with('_') && !known.contains(k))?;
    Some((key.to_owned(), unknown(key, known)))
}

/// Why key `key` is refused where `known` are taken: the nearest known key, the list, and
/// the rule for comments.
fn unknown(key: &str, known: &[&str]) -> String {
    let nearest = known
        .iter()
        .min_by_key(|k| strsim::damerau_levenshtein(key, k))
        .map(|k| format!("did you mean `{k}`? "))
        .unwrap_or_default();
    let list = known
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "unknown key `{key}`: {nearest}(this record takes {list}; keys beginning with `_` are \
         ignored)"
    )
}

#[cfg(test)]
mod tests {
    use super::{first_unknown, unknown_key};

    #[test]
    fn an_unknown_key_is_told_with_the_nearest_known_one() {
        let serde = "unknown field `delat`, expected one of `delta`, `robots`, `obstacles`, \
                     `tasks` at line 3 column 9";
        let (key, said) = unknown_key(serde).unwrap();
        assert_eq!(key, "delat");
        assert!(
            said.starts_with("unknown key `delat`: did you mean `delta`?"),
            "{said}"
        );
        assert!(said.ends_with("are ignored) at line 3 column 9"), "{said}");
        assert!(
            said.contains("`delta`, `robots`, `obstacles`, `tasks`"),
            "{said}"
        );
        let (_, said) = unknown_key("unknown field `robot`, expected `name` or `robots`").unwrap();
        assert!(said.contains("did you mean `robots`?"), "{said}");
        assert_eq!(unknown_key("missing field `home`"), None);
        let known = ["robot", "before_move", "duration"];
        assert_eq!(first_unknown(["robot", "_why", "duration"], &known), None);
        let (key, said) = first_unknown(["robot", "befor_move"], &known).unwrap();
        assert_eq!(key, "befor_move");
        assert!(said.contains("did you mean `before_move`?"), "{said}");
    }
}
