// A tiny grammar that proves the Debian ANTLR tool (4.7.2) and runtime (4.9)
// work together in this build; the ST and IL grammars use the same CMake
// function (cmake/Antlr.cmake).
grammar Smoke;

sum   : product (('+' | '-') product)* EOF ;
product : atom (('*' | '/') atom)* ;
atom  : INT | '(' sumInner ')' ;
sumInner : product (('+' | '-') product)* ;

INT : [0-9]+ ;
WS  : [ \t\r\n]+ -> skip ;
