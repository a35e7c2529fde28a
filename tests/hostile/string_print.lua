-- print() of 10 MB with terminal escapes: one line of at most 4 KiB reaches the log, escaped.
-- no-control
-- expect: \x1b]0;pwned\x07
-- expect: more bytes)
function PopulateWorld(world)
  print("\27]0;pwned\7" .. string.rep("\27[2J", 2500000))
end
