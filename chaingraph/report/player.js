(function () {
  var player = document.getElementById('player');
  var svg = document.querySelector('#stage svg');
  var groups = Array.prototype.slice.call(svg.querySelectorAll('g.frame'));
  groups.forEach(function (g) {       // the script drives the frames: SMIL off
    Array.prototype.slice.call(g.querySelectorAll('animate')).forEach(function (a) { a.remove(); });
  });
  var sliders = Array.prototype.slice.call(player.querySelectorAll('input.input-slider'));
  var marker = document.getElementById('marker');
  var button = document.getElementById('play');
  var n = groups.length, frame = 0, timer = null, grid = PLAYER.grid || 0;
  function show(i) {
    frame = i;
    groups.forEach(function (g, k) { g.setAttribute('visibility', k === i ? 'visible' : 'hidden'); });
    sliders.forEach(function (s) {
      var n = +s.dataset.index;         // on a grid: the first input along a row
      var at = grid ? (n === 0 ? i % grid : Math.floor(i / grid)) : i;
      s.value = at;
      s.nextElementSibling.textContent = Number(PLAYER.inputs[n][at]).toPrecision(4);
    });
    if (marker && PLAYER.px && PLAYER.px[i] !== null) {
      marker.setAttribute('cx', PLAYER.px[i].toFixed(2));
      marker.setAttribute('cy', PLAYER.py[i].toFixed(2));
    }
    player.setAttribute('data-frame', i);
  }
  function pause() { if (timer) { clearInterval(timer); timer = null; } button.textContent = 'play'; }
  function play() {
    pause();
    timer = setInterval(function () { show((frame + 1) % n); }, 4000 / n);
    button.textContent = 'pause';
  }
  button.addEventListener('click', function () { if (timer) { pause(); } else { play(); } });
  sliders.forEach(function (s) {
    s.addEventListener('input', function () {
      pause();
      show(grid ? +sliders[0].value + grid * +sliders[1].value : +s.value);
    });
  });
  var asked = /frame=(\d+)/.exec(window.location.hash);
  if (asked) { pause(); show(Math.min(+asked[1], n - 1)); } else { show(0); play(); }
})();
