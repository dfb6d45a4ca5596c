// The first minute at the top of the controls: what break-away is, what the note
// claims, what to try first. Hidden once the person dismisses it (or starts the tour
// from it), and for good: the choice is remembered in the browser; "What is this?" in
// the header shows it again.

import { $ } from "../page/store.js";

const REMEMBERED = "breakaway.intro.hidden";

/** The remembered choice; a browser that keeps nothing (storage refused) shows it. */
function remembered() {
  try {
    return window.localStorage.getItem(REMEMBERED) === "1";
  } catch {
    return false;
  }
}

function remember(hidden) {
  try {
    if (hidden) window.localStorage.setItem(REMEMBERED, "1");
    else window.localStorage.removeItem(REMEMBERED);
  } catch {
    // not remembered: it shows again next time
  }
}

function show(visible) {
  $("intro").hidden = !visible;
  $("intro-show").hidden = visible;
}

export function wireIntro() {
  show(!remembered());
  $("intro-hide").addEventListener("click", () => {
    remember(true);
    show(false);
    $("preset").focus();
  });
  $("intro-show").addEventListener("click", () => {
    remember(false);
    show(true);
    $("intro").scrollIntoView({ block: "nearest" });
    $("intro-hide").focus();
  });
  $("intro-tour").addEventListener("click", () => {
    remember(true);
    show(false);
    $("tour-start").click();
    $("tour-next").focus();
  });
}
