//! Issue 57: the page's operation forms come from the core (`Operation::forms`, one per kind,
//! written next to the kind's options). Each form is held to its options: every field edits a
//! setting the kind has; every setting has a field or is named as kept out; each choice is a
//! value the job file takes; a field that may be left empty is one the options leave empty; a
//! default lies in its field's range, and a value under a field's least of 0 is refused.

use serde_json::{json, Value};
use swarf::machining::form::{FieldInput, OperationForm};
use swarf::operations::Operation;

fn defaults() -> Vec<(OperationForm, Value)> {
    let forms = Operation::forms();
    let ops = Operation::defaults();
    assert_eq!(forms.len(), ops.len());
    forms.into_iter().zip(ops).map(|(f, o)| (f, serde_json::to_value(&o).unwrap())).collect()
}

/// The value at dotted `key` in `v`.
fn at<'a>(v: &'a Value, key: &str) -> Option<&'a Value> {
    key.split('.').try_fold(v, |v, k| v.get(k))
}

fn set(v: &mut Value, key: &str, to: Value) {
    let mut place = v;
    let parts: Vec<_> = key.split('.').collect();
    for k in &parts[..parts.len() - 1] {
        place = place.get_mut(*k).unwrap();
    }
    place[*parts.last().unwrap()] = to;
}

/// Every setting of `v`, dotted into its objects.
fn leaves(v: &Value, prefix: &str, out: &mut Vec<String>) {
    for (k, x) in v.as_object().unwrap() {
        let key = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match x {
            Value::Object(_) => leaves(x, &key, out),
            _ => out.push(key),
        }
    }
}

#[test]
fn every_form_is_its_kinds_own() {
    for (form, op) in defaults() {
        let kind = op["kind"].as_str().unwrap();
        assert_eq!(form.kind, kind, "forms in the kinds' order");
        assert!(!form.title.is_empty());
        let mut seen = std::collections::HashSet::new();
        for f in &form.fields {
            assert!(seen.insert(f.key), "{kind}: {} twice", f.key);
            assert!(at(&op, f.key).is_some(), "{kind}: the form's {} is no setting of the kind", f.key);
            assert!(!form.kept_out.contains(&f.key), "{kind}: {} both in the form and kept out", f.key);
        }
        let mut keys = Vec::new();
        leaves(&op, "", &mut keys);
        for key in keys.iter().filter(|k| *k != "kind" && *k != "enabled") {
            assert!(form.fields.iter().any(|f| f.key == key) || form.kept_out.contains(&key.as_str()), "{kind}: the setting {key} has no field in the page's form");
        }
    }
}

#[test]
fn every_choice_reads_and_every_default_is_in_range() {
    for (form, op) in defaults() {
        let kind = op["kind"].as_str().unwrap().to_owned();
        for f in &form.fields {
            let default = at(&op, f.key).unwrap().clone();
            // A setting the options leave empty by default is one its field may leave empty.
            if default.is_null() {
                assert!(f.empty.is_some(), "{kind}: {} is empty by default, and its field does not say what empty means", f.key);
            }
            if f.empty.is_some() {
                let mut v = op.clone();
                set(&mut v, f.key, if matches!(f.input, FieldInput::Ints | FieldInput::Words) { json!([]) } else { Value::Null });
                assert!(serde_json::from_value::<Operation>(v).is_ok(), "{kind}: {} left empty does not read", f.key);
            }
            match f.input {
                FieldInput::Choice => {
                    assert!(f.choices.len() >= 2, "{kind}: {} has fewer than two choices", f.key);
                    assert!(f.choices.iter().any(|c| default == json!(c.value)), "{kind}: {}'s default {default} is none of its choices", f.key);
                    for c in &f.choices {
                        let mut v = op.clone();
                        set(&mut v, f.key, json!(c.value));
                        assert!(serde_json::from_value::<Operation>(v).is_ok(), "{kind}: {} = {} does not read", f.key, c.value);
                    }
                }
                FieldInput::Number | FieldInput::Int => {
                    if let Some(x) = default.as_f64() {
                        assert!(f.min.is_none_or(|m| x >= m) && f.max.is_none_or(|m| x <= m), "{kind}: {}'s default {x} is outside its field's range {:?}..{:?}", f.key, f.min, f.max);
                    }
                    if f.min == Some(0.0) {
                        let mut v = op.clone();
                        set(&mut v, f.key, json!(-1.0));
                        let refused = match serde_json::from_value::<Operation>(v) {
                            Ok(o) => o.op().validate().is_err(),
                            Err(_) => true,
                        };
                        assert!(refused, "{kind}: {} = -1 is taken, under its field's least of 0", f.key);
                    }
                }
                FieldInput::Check => assert!(default.is_boolean(), "{kind}: {} is no yes or no", f.key),
                FieldInput::Ints | FieldInput::Words => assert!(default.is_array(), "{kind}: {} is no list", f.key),
                FieldInput::Text => assert!(default.is_string(), "{kind}: {} is no text", f.key),
                FieldInput::Tool => assert!(default.is_u64(), "{kind}: {} is no tool number", f.key),
            }
        }
    }
}
