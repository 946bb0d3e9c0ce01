" Okuma and Fanuc lathe programs: the file type `turnpass` (see ../syntax/turnpass.vim).
autocmd BufRead,BufNewFile *.min,*.MIN,*.ssb,*.SSB,*.sub,*.SUB,*.nc,*.NC setfiletype turnpass
