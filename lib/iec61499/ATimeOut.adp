<?xml version="1.0" encoding="UTF-8"?>
<!-- netlift library: ATimeOut, 4diac's timeout adapter (the plug side sends START with DT or STOP, the socket side answers TimeOut). Written for netlift. -->
<AdapterType Name="ATimeOut" Comment="timeout service">
  <InterfaceList>
    <EventInputs>
      <Event Name="TimeOut"/>
    </EventInputs>
    <EventOutputs>
      <Event Name="START"><With Var="DT"/></Event>
      <Event Name="STOP"/>
    </EventOutputs>
    <InputVars/>
    <OutputVars>
      <VarDeclaration Name="DT" Type="TIME"/>
    </OutputVars>
  </InterfaceList>
</AdapterType>
