//! What a server's or model's text may look like when shown: cut to a length a terminal line and
//! a report field can hold (the caller masks the API key first, see `mask`).

/// Cuts a message to 300 characters.
pub(crate) fn shorten(text: &str) -> String {
    if text.chars().count() > 300 {
        let cut: String = text.chars().take(297).collect();
        format!("{cut}...")
    } else {
        text.to_string()
    }
}
