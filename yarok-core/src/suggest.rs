//! "Did you mean …?" for unknown names.

/// The candidate closest to `name` by edit distance, when it is close enough to be a typo (at
/// most a third of the longer name's characters differ).
pub fn nearest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|candidate| (distance(name, candidate), candidate))
        .filter(|(d, candidate)| {
            *d <= (candidate.chars().count().max(name.chars().count()) / 3).max(1)
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, candidate)| candidate)
}

/// "; did you mean `x`?" or "", to end an error message about an unknown `name`.
///
/// # Examples
///
/// ```
/// use yarok_core::suggest::did_you_mean;
///
/// assert_eq!(did_you_mean("gripe", ["gripper", "arm"]), "; did you mean `gripper`?");
/// assert_eq!(did_you_mean("camera", ["gripper", "arm"]), "");
/// ```
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    nearest(name, candidates)
        .map(|n| format!("; did you mean `{n}`?"))
        .unwrap_or_default()
}

/// [`did_you_mean`], or when nothing is close, "; it has `a`, `b`, …" (sorted, at most
/// twelve): for names a user must take from a file they did not write.
///
/// # Examples
///
/// ```
/// use yarok_core::suggest::did_you_mean_or_list;
///
/// assert_eq!(did_you_mean_or_list("gripe", ["gripper", "arm"]), "; did you mean `gripper`?");
/// assert_eq!(
///     did_you_mean_or_list("fingers", ["fingers_actuator", "base"]),
///     "; it has `base`, `fingers_actuator`"
/// );
/// ```
pub fn did_you_mean_or_list<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> String {
    const LISTED: usize = 12;
    let mut all: Vec<&str> = candidates.into_iter().collect();
    let hint = did_you_mean(name, all.iter().copied());
    if !hint.is_empty() {
        return hint;
    }
    all.sort_unstable();
    all.dedup();
    if all.is_empty() {
        return "; it has none".to_owned();
    }
    let listed: Vec<String> = all.iter().take(LISTED).map(|n| format!("`{n}`")).collect();
    let more = all.len().saturating_sub(LISTED);
    let tail = if more > 0 {
        format!(" and {more} more")
    } else {
        String::new()
    };
    format!("; it has {}{tail}", listed.join(", "))
}

fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitution = previous + usize::from(ca != *cb);
            previous = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(previous + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    #[test]
    fn suggests_close_names_only() {
        assert_eq!(super::nearest("sped", ["speed", "rows"]), Some("speed"));
        assert_eq!(super::nearest("zzzz", ["speed", "rows"]), None);
        assert_eq!(
            super::did_you_mean("row", ["rows"]),
            "; did you mean `rows`?"
        );
    }
}
