// The book's sliders (tools/book_html.py writes their HTML): the method left of the line, the
// truth (or the method's error) right of it; dragging anywhere on the picture moves the line.
'use strict';

function setUpComparison(fig) {
  const view = fig.querySelector('.compare-view');
  const left = fig.querySelector('.compare-left');
  const right = fig.querySelector('.compare-right');
  const range = fig.querySelector('.compare-range');
  const tagLeft = fig.querySelector('.compare-tag-left');
  const tagRight = fig.querySelector('.compare-tag-right');
  const showTruth = fig.querySelector('.compare-show-truth');
  const showError = fig.querySelector('.compare-show-error');
  let errorShown = false;

  const split = () => view.style.setProperty('--split', (range.value / 10) + '%');
  range.addEventListener('input', split);
  // The range is invisible over the picture: arrow keys move the line in visible steps.
  range.addEventListener('keydown', (e) => {
    const step = {ArrowLeft: -25, ArrowDown: -25, ArrowRight: 25, ArrowUp: 25}[e.key];
    if (!step) return;
    e.preventDefault();
    range.value = Math.min(1000, Math.max(0, Number(range.value) + step));
    range.dispatchEvent(new Event('input'));
  });

  const update = () => {
    const error = left.dataset.error;
    if (!error) errorShown = false;
    showError.disabled = !error;
    right.src = errorShown ? error : fig.dataset.truth;
    right.alt = errorShown ? 'error of ' + left.alt : showTruth.textContent;
    tagRight.innerHTML = errorShown ? 'error of ' + tagLeft.innerHTML : showTruth.innerHTML;
    showTruth.setAttribute('aria-pressed', String(!errorShown));
    showError.setAttribute('aria-pressed', String(errorShown));
  };
  for (const button of fig.querySelectorAll('.compare-method')) {
    button.addEventListener('click', () => {
      for (const b of fig.querySelectorAll('.compare-method')) b.setAttribute('aria-pressed', String(b === button));
      left.src = button.dataset.src;
      left.alt = button.textContent;
      if (button.dataset.error) left.dataset.error = button.dataset.error; else delete left.dataset.error;
      tagLeft.innerHTML = button.innerHTML;
      update();
    });
  }
  showTruth.addEventListener('click', () => { errorShown = false; update(); });
  showError.addEventListener('click', () => { errorShown = true; update(); });
  split();
  update();
}

document.querySelectorAll('figure.compare').forEach(setUpComparison);
