// The atlas index's filter: shows the rows (tr.chain) that match the form's fields
// (base chain, numbers of sliding pairs and of multiple joints, named inversions only:
// the rows' data attributes; a text: the rows' own text, names, links, chain numbers),
// hides the groups left empty, and says how many are shown, in all and by group. No other asset: the page
// is opened from disk.
(function () {
  var rows = Array.prototype.slice.call(document.querySelectorAll('tr.chain'));
  var groups = Array.prototype.slice.call(document.querySelectorAll('section.group'));
  function field(id) { return document.getElementById(id); }
  function value(id) { var f = field(id); return f ? f.value : ''; }
  function apply() {
    var base = value('f-base'), sliding = value('f-sliding'), multiple = value('f-multiple');
    var named = field('f-named') && field('f-named').checked;
    var text = value('f-text').trim().toLowerCase();
    var shown = 0;
    rows.forEach(function (r) {
      var ok = (!base || r.getAttribute('data-base') === base) &&
        (!sliding || r.getAttribute('data-sliding') === sliding) &&
        (!multiple || r.getAttribute('data-multiple') === multiple) &&
        (!named || r.getAttribute('data-named') === '1') &&
        (!text || r.textContent.toLowerCase().indexOf(text) >= 0);
      r.hidden = !ok;
      if (ok) { shown += 1; }
    });
    groups.forEach(function (g) {
      var left = g.querySelectorAll('tr.chain:not([hidden])').length;
      g.querySelector('.shown').textContent = left;
      g.hidden = !left;
    });
    field('f-shown').textContent = shown + ' of ' + rows.length + ' chains shown';
  }
  ['f-base', 'f-sliding', 'f-multiple', 'f-named', 'f-text'].forEach(function (id) {
    if (field(id)) {
      field(id).addEventListener('input', apply);
      field(id).addEventListener('change', apply);
    }
  });
  field('filter').hidden = false;
  apply();                     // a browser may restore the fields on going back
}());
