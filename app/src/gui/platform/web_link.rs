//! A link's files on the web page: fetched from the page's own site (a
//! URL relative to the page), and the page's address for Copy link.

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

/// Fetches `url` (relative to the page) and gives its bytes, or why there
/// are none (a 404 said with the URL), to `done` on the page's thread.
pub fn fetch(url: &str, done: impl FnOnce(Result<Vec<u8>, String>) + 'static) {
    let url = url.to_string();
    wasm_bindgen_futures::spawn_local(async move {
        let bytes = fetched(&url).await.map_err(|e| {
            format!(
                "{url}: {}",
                e.as_string().unwrap_or_else(|| format!("{e:?}"))
            )
        });
        done(bytes);
    });
}

/// The bytes at `url` (relative to the page), or why there are none.
pub async fn fetched(url: &str) -> Result<Vec<u8>, JsValue> {
    let window = web_sys::window().ok_or_else(|| JsValue::from_str("no window"))?;
    let response: web_sys::Response = JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|_| JsValue::from_str("the page's site did not answer"))?
        .dyn_into()?;
    if !response.ok() {
        return Err(JsValue::from_str(&format!(
            "the page's site has no such file ({} {})",
            response.status(),
            response.status_text()
        )));
    }
    let buffer = JsFuture::from(response.array_buffer()?).await?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// The page's address without its query, for Copy link.
pub fn page_address() -> String {
    web_sys::window()
        .map(|w| w.location())
        .and_then(|l| Some(format!("{}{}", l.origin().ok()?, l.pathname().ok()?)))
        .unwrap_or_default()
}
