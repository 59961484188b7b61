//! Values in templates: instance config, `{expressions}` in attributes, and their scope.

use super::Composer;
use crate::compose::ComposeError;
use crate::compose::loader::Loaded;
use crate::compose::segments::{Segment, segments, whole_expression};
use crate::template::expr::{Expr, Variables};
use crate::template::xml::{Attribute, Element};
use crate::value::{Config, IntoValue, Value, typed};

/// Config values and loop variables, innermost last.
pub(super) struct Scope<'a> {
    pub(super) parent: Option<&'a Scope<'a>>,
    pub(super) vars: Vec<(String, Value)>,
}

impl Variables for Scope<'_> {
    fn get(&self, name: &str) -> Option<&Value> {
        match self.vars.iter().rev().find(|(n, _)| n == name) {
            Some((_, value)) => Some(value),
            None => self.parent.and_then(|p| p.get(name)),
        }
    }
}

impl Composer<'_> {
    /// Config of a new instance: defaults < tag attributes < overrides for its path.
    pub(super) fn configure(
        &mut self,
        loaded: &Loaded,
        path: &str,
        assigned: Vec<(Attribute, Value)>,
        tag: Option<&Element>,
    ) -> Result<Config, ComposeError> {
        let mut config = loaded.defaults.clone();
        for (attribute, value) in assigned {
            let typed = typed(&loaded.defaults, &attribute.name, value);
            let element = tag.cloned().unwrap_or_else(|| Element::new(&loaded.tag));
            let typed = typed.map_err(|m| self.error(&element, Some(&attribute), None, m))?;
            config.set(&attribute.name, typed);
        }
        if let Some(overrides) = self.overrides.get(path) {
            self.used_overrides.insert(path.to_owned());
            for (key, value) in overrides.iter() {
                let typed = typed(&loaded.defaults, key, value.clone())
                    .map_err(|m| self.override_error(path, key, m))?;
                config.set(key, typed);
            }
        }
        Ok(config)
    }

    pub(super) fn attribute_value(
        &mut self,
        attribute: &Attribute,
        element: &Element,
        scope: &Scope<'_>,
    ) -> Result<Value, ComposeError> {
        match whole_expression(&attribute.value) {
            Some(source) => self.eval(source, element, Some(attribute), scope),
            None => Ok(self.interpolated(attribute, element, scope)?.into_value()),
        }
    }

    pub(super) fn interpolate(
        &mut self,
        element: &mut Element,
        scope: &Scope<'_>,
    ) -> Result<(), ComposeError> {
        for index in 0..element.attributes.len() {
            if element.attributes[index].value.contains(['{', '}']) {
                let value = self.interpolated(&element.attributes[index], element, scope)?;
                element.attributes[index].value = value;
            }
        }
        Ok(())
    }

    pub(super) fn interpolated(
        &mut self,
        attribute: &Attribute,
        element: &Element,
        scope: &Scope<'_>,
    ) -> Result<String, ComposeError> {
        let mut out = String::with_capacity(attribute.value.len());
        for segment in
            segments(&attribute.value).map_err(|m| self.error(element, Some(attribute), None, m))?
        {
            match segment {
                Segment::Text(text) => out.push_str(text),
                Segment::Expression(source) => {
                    let value = self.eval(source, element, Some(attribute), scope)?;
                    out.push_str(&value.to_string());
                }
            }
        }
        Ok(out)
    }

    pub(super) fn eval(
        &mut self,
        source: &str,
        element: &Element,
        attribute: Option<&Attribute>,
        scope: &Scope<'_>,
    ) -> Result<Value, ComposeError> {
        if !self.expressions.contains_key(source) {
            let parsed = Expr::parse(source)
                .map_err(|e| self.error(element, attribute, Some(source), e.to_string()))?;
            self.expressions.insert(source.to_owned(), parsed);
        }
        self.expressions[source]
            .eval(scope)
            .map_err(|e| self.error(element, attribute, Some(source), e.to_string()))
    }
}
