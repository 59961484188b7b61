use std::collections::HashMap;

use evalexpr::Value;

use super::{Expr, Variables};
use crate::value::format_value;

struct Vars(HashMap<&'static str, crate::value::Value>);

impl Variables for Vars {
    fn get(&self, name: &str) -> Option<&crate::value::Value> {
        self.0.get(name)
    }
}

fn vars() -> Vars {
    Vars(HashMap::from_iter(
        [
            ("x", Value::Int(2)),
            ("z", Value::Int(3)),
            ("n", Value::Int(4)),
            (
                "lst",
                Value::Tuple(vec![
                    Value::Float(0.1),
                    Value::Float(0.2),
                    Value::Float(0.3),
                ]),
            ),
            ("name", Value::String("arm".into())),
            ("flag", Value::Boolean(true)),
        ]
        .map(|(name, value)| (name, crate::value::Value(value))),
    ))
}

fn eval(source: &str) -> Value {
    Expr::parse(source)
        .unwrap_or_else(|e| panic!("{source}: {e}"))
        .eval(&vars())
        .unwrap_or_else(|e| panic!("{source}: {e}"))
        .0
}

fn show(source: &str) -> String {
    format_value(&eval(source))
}

fn error(source: &str) -> String {
    match Expr::parse(source) {
        Err(e) => e.to_string(),
        Ok(expr) => expr.eval(&vars()).expect_err(source).to_string(),
    }
}

#[test]
fn the_original_readme_expressions_work_verbatim() {
    assert_eq!(show("0.5 + 0.082*x if z % 2 == 0 else 0.58"), "0.58");
    assert_eq!(show("0.5 + 0.082*x if z % 2 == 1 else 0.58"), "0.664");
    assert_eq!(show("0 if z % 2 == 0 else 1.57"), "1.57");
    assert_eq!(show("range(n)"), "0 1 2 3");
    assert_eq!(show("0.061*z"), format!("{}", 0.061 * 3.0));
}

#[test]
fn arithmetic_follows_python() {
    assert_eq!(eval("1/2"), Value::Float(0.5));
    assert_eq!(eval("7//2"), Value::Int(3));
    assert_eq!(eval("-7//2"), Value::Int(-4));
    assert_eq!(eval("-7 % 3"), Value::Int(2));
    assert_eq!(eval("7 % -3"), Value::Int(-2));
    assert_eq!(eval("-7.5 % 2"), Value::Float(0.5));
    assert_eq!(eval("2**10"), Value::Int(1024));
    assert_eq!(eval("2**-1"), Value::Float(0.5));
    assert_eq!(eval("-2**2"), Value::Int(-4));
    assert_eq!(eval("1 == 1.0"), Value::Boolean(true));
    assert_eq!(eval("0 < x < 3"), Value::Boolean(true));
    assert_eq!(eval("0 < x < 2"), Value::Boolean(false));
    assert_eq!(eval("1 + 2 * 3 - 4"), Value::Int(3));
    assert_eq!(eval("(1 + 2) * 3"), Value::Int(9));
    assert_eq!(eval("0.1 + 0.2"), Value::Float(0.1 + 0.2));
    assert_eq!(eval("1e-3 * 2"), Value::Float(0.002));
}

#[test]
fn logic_membership_and_conditionals() {
    assert_eq!(eval("flag and x > 1"), Value::Boolean(true));
    assert_eq!(eval("not flag or x"), Value::Int(2));
    assert_eq!(eval("2 in range(n)"), Value::Boolean(true));
    assert_eq!(eval("5 not in range(n)"), Value::Boolean(true));
    assert_eq!(eval("'r' in name"), Value::Boolean(true));
    assert_eq!(eval("'a' if x else 'b'"), Value::String("a".into()));
    // Only the branch taken is evaluated, as in Python.
    assert_eq!(eval("lst[9] if x > 5 else 0"), Value::Int(0));
    assert_eq!(eval("1 if x > 5 else 2 if x > 1 else 3"), Value::Int(2));
    assert_eq!(eval("(1 if flag else 2) + 10"), Value::Int(11));
}

#[test]
fn sequences_indexing_and_builtins() {
    assert_eq!(show("lst"), "0.1 0.2 0.3");
    assert_eq!(eval("lst[0]"), Value::Float(0.1));
    assert_eq!(eval("lst[-1]"), Value::Float(0.3));
    assert_eq!(show("lst[1:]"), "0.2 0.3");
    assert_eq!(show("[x, x * 2, 0.5]"), "2 4 0.5");
    assert_eq!(show("(1, 2) + (3,)"), "1 2 3");
    assert_eq!(eval("len(lst)"), Value::Int(3));
    assert_eq!(eval("len([lst])"), Value::Int(1));
    assert_eq!(eval("max(lst)"), Value::Float(0.3));
    assert_eq!(eval("min(3, 1, 2)"), Value::Int(1));
    assert_eq!(eval("sum(range(5))"), Value::Int(10));
    assert_eq!(eval("round(2.5)"), Value::Int(2));
    assert_eq!(eval("round(0.126, 2)"), Value::Float(0.13));
    assert_eq!(eval("int('7') + int(2.9)"), Value::Int(9));
    assert_eq!(eval("str(x) + name"), Value::String("2arm".into()));
    assert_eq!(show("list(range(2, 8, 3))"), "2 5");
    assert_eq!(show("range(3, 0, -1)"), "3 2 1");
    assert_eq!(eval("math.cos(math.pi)"), Value::Float(-1.0));
    assert_eq!(eval("name[0]"), Value::String("a".into()));
}

#[test]
fn values_print_for_mjcf() {
    assert_eq!(show("0.1 * 3"), format!("{}", 0.1 * 3.0));
    assert_eq!(show("1.0"), "1");
    assert_eq!(show("True"), "true");
    assert_eq!(show("[1, [2, 3]]"), "1 2 3");
    assert_eq!(show("1e-7").parse::<f64>().unwrap(), 1e-7);
}

#[test]
fn errors_say_what_went_wrong() {
    assert_eq!(error("y + 1"), "name `y` is not defined");
    assert_eq!(error("1 / 0"), "division by zero");
    assert_eq!(error("lst[3]"), "list index 3 out of range (length 3)");
    assert_eq!(
        error("'a' + 1"),
        "unsupported operand types for +: 'str' and 'int'"
    );
    assert_eq!(
        error("1 +"),
        "unexpected end of expression (at character 4)"
    );
    assert_eq!(
        error("x if x"),
        "expected `else` in `a if condition else b` (at character 7)"
    );
    assert_eq!(error("open('f')"), "function `open` is not defined");
    assert_eq!(
        error("__import__('os')"),
        "function `__import__` is not defined"
    );
    assert_eq!(error("x = 1"), "unexpected character '=' (at character 3)");
    assert_eq!(
        error("range(10**9)"),
        "range() of 1000000000 items is longer than 1000000"
    );
    assert_eq!(error("9223372036854775807 + 1"), "integer overflow in +");
    assert_eq!(error("math.system"), "name `math.system` is not defined");
    assert!(error(&"(".repeat(200)).contains("nested too deeply"));
}

#[test]
fn conditionals_nested_in_arithmetic_see_variables() {
    assert_eq!(eval("lst[0] + (0.5 if x else 1)"), Value::Float(0.6));
    assert_eq!(eval("x + (1 if x > 5 else lst[1])"), Value::Float(2.2));
}

#[test]
fn and_or_and_chained_comparisons_stop_where_python_stops() {
    // Python never evaluates what does not decide the result: no error from the part skipped.
    assert_eq!(eval("0 and 1 / 0"), Value::Int(0));
    assert_eq!(eval("[] or 7 or undefined_name"), Value::Int(7));
    assert_eq!(eval("x or undefined_name"), Value::Int(2));
    assert_eq!(eval("3 < 2 < 1 / 0"), Value::Boolean(false));
    assert_eq!(eval("'' and 1"), Value::String(String::new()));
    assert_eq!(
        error("1 < 2 < undefined_name"),
        "name `undefined_name` is not defined"
    );
}

#[test]
fn long_flat_chains_evaluate_without_deep_recursion() {
    let sum = vec!["1"; 100_000].join(" + ");
    assert_eq!(eval(&sum), Value::Int(100_000));
    let mixed = format!("{} - 1", vec!["2 * 3 // 2"; 50_000].join(" + "));
    assert_eq!(eval(&mixed), Value::Int(149_999));
    let conjunction = vec!["True"; 100_000].join(" and ");
    assert_eq!(eval(&conjunction), Value::Boolean(true));
    assert_eq!(eval(&format!("{conjunction} and 0 and 1")), Value::Int(0));
    assert_eq!(eval("0 or '' or 7 or 8"), Value::Int(7));
    assert_eq!(eval("0 or ''"), Value::String(String::new()));
}

#[test]
fn loop_variables_are_names_that_are_not_keywords() {
    for name in ["leg", "_b2", "true", "größe"] {
        assert!(super::is_variable_name(name), "{name}");
    }
    for name in ["1x", "True", "None", "if", "a b", "a.b", "", "x+1"] {
        assert!(!super::is_variable_name(name), "{name}");
    }
}

#[test]
fn an_expression_that_gives_nan_or_inf_is_an_error() {
    for source in [
        "0 ** -1",
        "0.0 ** -1",
        "float('nan')",
        "[1, float('inf')]",
        "1e308 * 10",
    ] {
        let said = error(source);
        assert!(said.contains("not a finite number"), "{source}: {said}");
    }
    assert_eq!(show("float('1e3')"), "1000");
}
