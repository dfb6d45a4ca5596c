// The data panel's quiz: a mystery sample shows the data, the base model and its
// residual first; the learner guesses what the base model misses, and only then does
// the panel show the diagnosis and whether the guess was right.

import { element } from "./fitview.js";

const $ = (id) => document.getElementById(id);

let unrevealed = null; // the report of a quiz not yet answered

/** The right answer of a finished report: its effects, "none" or "outside". */
export function quizAnswer(report) {
  if (report.effects.length) return report.effects;
  return report.unexplained ? "outside" : "none";
}

/** Whether `guess` (an effect name, "none" or "outside") is right for `report`. */
export function quizRight(guess, report) {
  const answer = quizAnswer(report);
  return Array.isArray(answer) ? answer.includes(guess) : guess === answer;
}

/** True while a quiz waits for its guess (the panel then hides the diagnosis). */
export function quizPending() {
  return unrevealed !== null;
}

/** Pose the quiz for a finished report. */
export function startQuiz(report) {
  unrevealed = report;
  const select = $("quiz-guess");
  select.replaceChildren(element("option", { value: "", text: "(choose)" }),
    // the library's effects for this kind, as the engine's registry lists them: the
    // report names every one in its candidates
    ...Object.keys(report.candidates ?? {}).map((e) => element("option", { value: e, text: e })),
    element("option", { value: "none", text: "nothing: the base model explains it" }),
    element("option", { value: "outside", text: "something the library does not have" }));
  $("quiz-reveal").disabled = true;
  $("quiz-result").textContent = "";
  $("quiz").hidden = false;
  $("fit-results").classList.add("quiz-hidden");
}

/** No quiz: hidden, and the results shown in full. */
export function endQuiz() {
  unrevealed = null;
  $("quiz").hidden = true;
  $("fit-results").classList.remove("quiz-hidden");
}

function reveal(onReveal) {
  const guess = $("quiz-guess").value;
  if (!unrevealed || !guess) return;
  const report = unrevealed;
  const answer = quizAnswer(report);
  const truth = Array.isArray(answer) ? `the data hold ${answer.join(" and ")}`
    : answer === "none" ? "nothing is missing: the base model explains the data"
      : "the residual keeps structure that no effect of the library explains";
  $("quiz-result").textContent = quizRight(guess, report)
    ? `Right: ${truth}.` : `Not this time: ${truth}.`;
  $("quiz-result").dataset.right = String(quizRight(guess, report));
  unrevealed = null;
  $("fit-results").classList.remove("quiz-hidden");
  onReveal();
}

/** Wire the quiz; `onReveal()` shows the full results once the guess is made. */
export function wireQuiz(onReveal) {
  $("quiz-guess").addEventListener("change", () => {
    $("quiz-reveal").disabled = !$("quiz-guess").value;
  });
  $("quiz-reveal").addEventListener("click", () => reveal(onReveal));
}
