(a student program for a denford lathe, written in lower case: on a control that reads)
(lower case, control = "denford" in the settings, it runs as its upper-case twin.)
%
o0001
g21 g99
t0101
g97 s1000 m03
g00 x40. z2.
g01 z-20. f0.2
x44.
g00 x200. z100.
m30
%
