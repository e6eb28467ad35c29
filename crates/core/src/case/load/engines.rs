//! `[engines.<id>]`: only the registry's engines, each with its step, distinct variants
//! and options (numbers, strings or booleans).

use std::collections::BTreeMap;

use super::super::raw::RawEngine;
use super::super::scene::{EngineRequest, OptionValue, quoted};
use super::validator::{Rule, Validator};

impl Validator<'_> {
    pub(super) fn engines(
        &mut self,
        raw: &BTreeMap<String, RawEngine>,
        duration: f64,
        output_dt: Option<f64>,
    ) -> BTreeMap<String, EngineRequest> {
        let mut out = BTreeMap::new();
        for (id, e) in raw {
            let field = format!("engines.{id}");
            if !self.engine_ids.contains(&id.as_str()) {
                let known = quoted(self.engine_ids);
                self.fail(
                    &field,
                    format!("unknown engine \"{id}\"; the engines are {known}"),
                );
                continue;
            }
            if let Some(dt) = e.dt {
                self.number(&format!("{field}.dt"), Some(dt), Rule::positive("s"));
                self.steps(&format!("{field}.dt"), duration, dt, output_dt);
            }
            self.distinct_variants(&field, e.variants.as_deref().unwrap_or_default());
            let mut options = BTreeMap::new();
            for (k, v) in &e.options {
                let value = match v {
                    toml::Value::Float(x) => OptionValue::Number(*x),
                    toml::Value::Integer(i) => OptionValue::Number(*i as f64),
                    toml::Value::String(s) => OptionValue::Text(s.clone()),
                    toml::Value::Boolean(b) => OptionValue::Bool(*b),
                    _ => {
                        self.fail(
                            &format!("{field}.{k}"),
                            "must be a number, a string or a boolean",
                        );
                        continue;
                    }
                };
                options.insert(k.clone(), value);
            }
            out.insert(
                id.clone(),
                EngineRequest {
                    dt: e.dt,
                    variants: e.variants.clone(),
                    options,
                },
            );
        }
        out
    }

    /// A variant named twice would run twice into one trace channel: an error at the repeat.
    pub(super) fn distinct_variants(&mut self, field: &str, variants: &[String]) {
        for (i, v) in variants.iter().enumerate() {
            if let Some(first) = variants[..i].iter().position(|w| w == v) {
                self.fail(
                    &format!("{field}.variants[{i}]"),
                    format!("\"{v}\" is already variants[{first}]; name each variant once"),
                );
            }
        }
    }

    pub(super) fn engine_id(&mut self, field: &str, engine: &str) {
        if !self.engine_ids.contains(&engine) {
            self.fail(
                field,
                format!(
                    "unknown engine \"{engine}\"; known: {}",
                    quoted(self.engine_ids)
                ),
            );
        }
    }
}
