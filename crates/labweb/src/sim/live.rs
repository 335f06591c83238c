//! Symbols that point at what they name (issue 27 §3). A symbol marked
//! `\live{key}{…}` on the Theory tab, or a quantity's symbol in "The math"
//! panel, is a focusable `[data-live="key"]` element. Hovering or focusing
//! it draws the scene's parts tagged with that key as a halo
//! ([`labcore::scene::Tag`]) and shows the quantity's value from the
//! student's current run in a tip (`θ1 = 35.0°`), a status region that
//! screen readers announce (in the panel, whose numbers stand under the
//! symbols, it is only read out).

use super::SimState;
use crate::dom::{query, Listener};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use web_sys::{Element, Event, HtmlElement};

/// Listens on the whole article (its Theory tab and the Simulation panel).
pub(super) fn listen(state: &Rc<RefCell<SimState>>, panel: &Element, out: &mut Vec<Listener>) {
    let Some(article) = panel.parent_element() else {
        return;
    };
    let _ = article.insert_adjacent_html(
        "beforeend",
        "<p class=\"live-tip\" role=\"status\" hidden></p>",
    );
    for (kind, on) in [
        ("mouseover", true),
        ("focusin", true),
        ("mouseout", false),
        ("focusout", false),
    ] {
        let s = state.clone();
        let tip = query(&article, ".live-tip");
        out.push(Listener::new(article.as_ref(), kind, move |e: Event| {
            let Some(symbol) = e
                .target()
                .and_then(|t| t.dyn_into::<Element>().ok())
                .and_then(|t| t.closest("[data-live]").ok().flatten())
            else {
                return;
            };
            if let (Ok(mut st), Some(tip)) = (s.try_borrow_mut(), &tip) {
                st.point_at(&symbol, tip, on);
            }
        }));
    }
}

impl SimState {
    /// Shows (`on`) or hides what `symbol` names: the halo in the scene and
    /// the value in `tip`, placed under the symbol.
    fn point_at(&mut self, symbol: &Element, tip: &Element, on: bool) {
        let key = symbol.get_attribute("data-live").filter(|_| on);
        let quantity = key
            .as_deref()
            .and_then(|k| self.quantities().into_iter().find(|q| q.key == k));
        let _ = match &key {
            Some(k) => self.canvas.set_attribute("data-live", k),
            None => self.canvas.remove_attribute("data-live"),
        };
        self.live_key = key;
        self.needs_paint = true;
        let Some(q) = quantity else {
            tip.set_attribute("hidden", "").ok();
            return;
        };
        let unit = if q.hidden { "" } else { q.unit };
        let space = if unit == "°" || unit.is_empty() {
            ""
        } else {
            " "
        };
        tip.set_text_content(Some(&format!(
            "{} = {}{space}{unit}",
            q.symbol.replace('_', ""),
            q.number_text(),
        )));
        let _ = tip.remove_attribute("hidden");
        // In "The math" the numbers already stand under the symbol: the tip
        // is only read out there, not drawn over them.
        let in_panel = symbol.closest(".live-math").ok().flatten().is_some();
        let _ = tip.class_list().toggle_with_force("sr-only", in_panel);
        let at = symbol.get_bounding_client_rect();
        if let Some(style) = tip.dyn_ref::<HtmlElement>().map(HtmlElement::style) {
            // Whole pixels, written without float formatting.
            let _ = style.set_property("left", &format!("{}px", at.left() as i32));
            let _ = style.set_property("top", &format!("{}px", at.bottom() as i32 + 6));
        }
    }
}
